#include "physics/local_contact_model.hpp"

namespace echosim::physics {

LocalContactModel local_contact_model(const CompiledModel& model, TissueState& s)
{
    const contact::PenaltyLaw& law = model.penalty;
    LocalContactModel m;
    m.time = s.time;
    m.step = s.steps;
    m.axis = s.contacts.axis;
    m.face = s.probe.position;
    m.force = s.contacts.total_force;
    m.speed = s.probe.velocity.dot(m.axis);
    m.in_contact = !s.contacts.contacts.empty();
    if (!m.in_contact) return m;

    // the penalty's stiffness acting at each node: sum over its samples of k_c w (a node moved by
    // u along the axis changes a sample's penetration by w u)
    std::vector<double>& penalty = s.node_scratch;
    for (const contact::Contact& c : s.contacts.contacts)
        for (int k = 0; k < 3; ++k) penalty[c.nodes[std::size_t(k)]] += c.stiffness * c.weights[k];

    // each node once: penalty in series with the column beneath, for stiffness and for damping
    for (const contact::Contact& c : s.contacts.contacts)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = c.nodes[std::size_t(k)];
            const double k_pen = penalty[i];
            if (k_pen <= 0.0) continue;  // done already (or a sample at zero weight)
            penalty[i] = 0.0;
            if (model.fixed(i)) {  // held to the leg: the penalty alone
                m.stiffness += k_pen;
                m.damping += law.damping_time * k_pen;
                continue;
            }
            const TissueColumn& col = model.columns[i];
            const double along = col.n.dot(m.axis), along2 = along * along;
            const double k_col = s.normal_stiffness[i] * along2 + col.lateral_stiffness * (1.0 - along2);
            const double d_col = col.damping * along2 + col.lateral_damping * (1.0 - along2);
            const double d_pen = law.damping_time * k_pen;
            m.stiffness += k_pen * k_col / (k_pen + k_col);
            m.damping += d_pen * d_col / (d_pen + d_col);
        }
    return m;
}

}  // namespace echosim::physics
