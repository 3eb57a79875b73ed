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

void system_product(const tissue::TissueModel& model, const TissueState& s, double h, const Eigen::VectorXd& p,
                    Eigen::VectorXd& out)
{
    for (std::size_t i = 0; i < model.node_count(); ++i)
        out.segment<3>(3 * Eigen::Index(i)) = (model.mass[i] * 1e-3) * p.segment<3>(3 * Eigen::Index(i));
    add_blocks(model, s, h, h * h, p, out);
    contact::add_contact_product(s.contacts, h * h, p, out);
    filter_fixed(s, p, out);
}

void stiffness_product(const tissue::TissueModel& model, const TissueState& s, const Eigen::VectorXd& p, Eigen::VectorXd& out)
{
    out.setZero();
    add_blocks(model, s, 0.0, 1.0, p, out);
    contact::add_contact_product(s.contacts, 1.0, p, out);
}

void system_diagonal(const tissue::TissueModel& model, const TissueState& s, double h, Eigen::VectorXd& out)
{
    for (std::size_t i = 0; i < model.node_count(); ++i) out.segment<3>(3 * Eigen::Index(i)).setConstant(model.mass[i] * 1e-3);
    const double h2 = h * h;
    for (std::size_t k = 0; k < model.springs.size(); ++k) {
        const tissue::Spring& sp = model.springs[k];
        const SpringLinearisation& lin = s.springs[k];
        const Eigen::Vector3d ee = lin.e.cwiseProduct(lin.e);
        const Eigen::Vector3d d = h2 * model.lambda * (lin.beta * Eigen::Vector3d::Ones() + (1.0 - lin.beta) * ee) + h * model.mu * ee;
        out.segment<3>(3 * Eigen::Index(sp.i)) += d;
        out.segment<3>(3 * Eigen::Index(sp.j)) += d;
    }
    for (std::size_t i = 0; i < model.node_count(); ++i) {
        const NormalLinearisation& lin = s.normals[i];
        const double k_n = h2 * lin.stiffness + h * lin.damping, k_t = h2 * lin.lateral_stiffness + h * lin.lateral_damping;
        out.segment<3>(3 * Eigen::Index(i)) += k_t * Eigen::Vector3d::Ones() + (k_n - k_t) * lin.n.cwiseProduct(lin.n);
    }
    for (const contact::Contact& c : s.contacts.contacts)
        for (int k = 0; k < 3; ++k)
            out.segment<3>(3 * Eigen::Index(c.nodes[std::size_t(k)])) +=
                h2 * c.stiffness * c.weights[k] * c.weights[k] * s.contacts.axis.cwiseProduct(s.contacts.axis);
    for (std::size_t i = 0; i < s.fixed.size(); ++i)
        if (s.fixed[i]) out.segment<3>(3 * Eigen::Index(i)).setOnes();
}

}  // namespace echosim::physics
