#include "physics/system_product.hpp"

namespace echosim::physics {
namespace {

// y += sd * (damping block) p + sk * (stiffness block) p, over all springs and normal springs
void add_blocks(const tissue::TissueModel& model, const TissueState& s, double sd, double sk, const Eigen::VectorXd& p,
                Eigen::VectorXd& y)
{
    for (std::size_t k = 0; k < model.springs.size(); ++k) {
        const tissue::Spring& sp = model.springs[k];
        const SpringLinearisation& lin = s.springs[k];
        const Eigen::Vector3d dp = p.segment<3>(3 * Eigen::Index(sp.i)) - p.segment<3>(3 * Eigen::Index(sp.j));
        const double along = lin.e.dot(dp);
        // stiffness: lambda (beta I + (1 - beta) e e^T); damping: mu e e^T
        const Eigen::Vector3d r = sk * model.lambda * (lin.beta * dp + (1.0 - lin.beta) * along * lin.e) + sd * model.mu * along * lin.e;
        y.segment<3>(3 * Eigen::Index(sp.i)) += r;
        y.segment<3>(3 * Eigen::Index(sp.j)) -= r;
    }
    for (std::size_t i = 0; i < model.node_count(); ++i) {
        const NormalLinearisation& lin = s.normals[i];
        const Eigen::Vector3d pi = p.segment<3>(3 * Eigen::Index(i));
        const double along = lin.n.dot(pi);
        const double k_n = sk * lin.stiffness + sd * lin.damping, k_t = sk * lin.lateral_stiffness + sd * lin.lateral_damping;
        y.segment<3>(3 * Eigen::Index(i)) += k_t * pi + (k_n - k_t) * along * lin.n;
    }
}

void filter_fixed(const TissueState& s, const Eigen::VectorXd& p, Eigen::VectorXd& y)
{
    for (std::size_t i = 0; i < s.fixed.size(); ++i)
        if (s.fixed[i]) y.segment<3>(3 * Eigen::Index(i)) = p.segment<3>(3 * Eigen::Index(i));
}

}  // namespace

void prepare_system(const tissue::TissueModel& model, TissueState& s, double h)
{
    const double h2 = h * h;
    for (SpringLinearisation& lin : s.springs) {
        lin.iso = h2 * model.lambda * lin.beta;
        lin.along = h2 * model.lambda * (1.0 - lin.beta) + h * model.mu;
    }
    for (NormalLinearisation& lin : s.normals) {
        const double k_n = h2 * lin.stiffness + h * lin.damping, k_t = h2 * lin.lateral_stiffness + h * lin.lateral_damping;
        lin.iso = k_t;
        lin.along = k_n - k_t;
    }
}

void system_product(const tissue::TissueModel& model, const contact::PenaltyLaw& law, const TissueState& s, double h,
                    const Eigen::VectorXd& p, Eigen::VectorXd& out)
{
    // mass and the tissue column under each node (prepared for this h by prepare_system)
    for (std::size_t i = 0; i < model.node_count(); ++i) {
        const NormalLinearisation& lin = s.normals[i];
        const Eigen::Vector3d pi = p.segment<3>(3 * Eigen::Index(i));
        out.segment<3>(3 * Eigen::Index(i)) = (model.mass[i] * 1e-3 + lin.iso) * pi + (lin.along * lin.n.dot(pi)) * lin.n;
    }
    // the surface springs
    for (std::size_t k = 0; k < model.springs.size(); ++k) {
        const tissue::Spring& sp = model.springs[k];
        const SpringLinearisation& lin = s.springs[k];
        const Eigen::Vector3d dp = p.segment<3>(3 * Eigen::Index(sp.i)) - p.segment<3>(3 * Eigen::Index(sp.j));
        const Eigen::Vector3d r = lin.iso * dp + (lin.along * lin.e.dot(dp)) * lin.e;
        out.segment<3>(3 * Eigen::Index(sp.i)) += r;
        out.segment<3>(3 * Eigen::Index(sp.j)) -= r;
    }
    contact::add_contact_product(s.contacts, law, h, h * h, p, out);
    filter_fixed(s, p, out);
}

void stiffness_product(const tissue::TissueModel& model, const contact::PenaltyLaw& law, const TissueState& s,
                       const Eigen::VectorXd& p, Eigen::VectorXd& out)
{
    out.setZero();
    add_blocks(model, s, 0.0, 1.0, p, out);
    contact::add_contact_product(s.contacts, law, 0.0, 1.0, p, out);
}

void system_block_inverses(const tissue::TissueModel& model, const contact::PenaltyLaw& law, const TissueState& s, double h,
                           std::vector<Eigen::Matrix3d>& out)
{
    const double h2 = h * h;
    for (std::size_t i = 0; i < model.node_count(); ++i) out[i] = (model.mass[i] * 1e-3) * Eigen::Matrix3d::Identity();
    for (std::size_t k = 0; k < model.springs.size(); ++k) {
        const tissue::Spring& sp = model.springs[k];
        const SpringLinearisation& lin = s.springs[k];
        const Eigen::Matrix3d ee = lin.e * lin.e.transpose();
        const Eigen::Matrix3d b = h2 * model.lambda * (lin.beta * Eigen::Matrix3d::Identity() + (1.0 - lin.beta) * ee) + h * model.mu * ee;
        out[sp.i] += b;
        out[sp.j] += b;
    }
    for (std::size_t i = 0; i < model.node_count(); ++i) {
        const NormalLinearisation& lin = s.normals[i];
        const double k_n = h2 * lin.stiffness + h * lin.damping, k_t = h2 * lin.lateral_stiffness + h * lin.lateral_damping;
        out[i] += k_t * Eigen::Matrix3d::Identity() + (k_n - k_t) * (lin.n * lin.n.transpose());
    }
    const Eigen::Matrix3d aa = s.contacts.axis * s.contacts.axis.transpose();
    for (const contact::Contact& c : s.contacts.contacts)
        for (int k = 0; k < 3; ++k)
            out[c.nodes[std::size_t(k)]] += ((h2 + h * law.damping_time) * c.stiffness * c.weights[k] * c.weights[k]) * aa;
    for (std::size_t i = 0; i < model.node_count(); ++i)
        out[i] = s.fixed[i] ? Eigen::Matrix3d::Identity() : Eigen::Matrix3d(out[i].inverse());
}

}  // namespace echosim::physics
