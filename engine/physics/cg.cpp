#include "physics/cg.hpp"

#include <cmath>

#include "physics/system_product.hpp"

namespace echosim::physics {

CgResult conjugate_gradient(const tissue::TissueModel& model, const PhysicsOptions& options, const contact::PenaltyLaw& law,
                            TissueState& s, double h)
{
    CgResult out;
    prepare_system(model, s, h);
    system_block_inverses(model, law, s, h, s.preconditioner);
    auto precondition = [&] {
        for (std::size_t i = 0; i < s.preconditioner.size(); ++i)
            s.z.segment<3>(3 * Eigen::Index(i)) = s.preconditioner[i] * s.residual.segment<3>(3 * Eigen::Index(i));
    };

    // r = b - A x0, from the warm start
    system_product(model, law, s, h, s.dv, s.product);
    s.residual = s.rhs - s.product;
    for (std::size_t i = 0; i < s.fixed.size(); ++i)
        if (s.fixed[i]) s.residual.segment<3>(3 * Eigen::Index(i)).setZero();
    const double rhs_norm = std::max(s.rhs.norm(), 1e-30);
    precondition();
    s.direction = s.z;
    double rz = s.residual.dot(s.z);
    for (; out.iterations < options.cg_max_iterations; ++out.iterations) {
        out.relative_residual = s.residual.norm() / rhs_norm;
        if (!std::isfinite(out.relative_residual)) {
            out.finite = false;
            return out;
        }
        if (out.relative_residual <= options.cg_tolerance) break;
        system_product(model, law, s, h, s.direction, s.product);
        const double pap = s.direction.dot(s.product);
        if (!(pap > 0)) break;  // the matrix is SPD: only round-off gets here, at convergence
        const double alpha = rz / pap;
        s.dv += alpha * s.direction;
        s.residual -= alpha * s.product;
        precondition();
        const double rz_next = s.residual.dot(s.z);
        s.direction = s.z + (rz_next / rz) * s.direction;
        rz = rz_next;
    }
    out.relative_residual = s.residual.norm() / rhs_norm;
    return out;
}

}  // namespace echosim::physics
