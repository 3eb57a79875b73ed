// The non-linear spring of the paper's eq. (1) that carries each surface node on the bone.
//
// The paper writes f(x) = x / (a x + b) with x the change of length (negative in compression) and
// a, b > 0. We use the compression c = -x >= 0 and the magnitude of the force pushing back:
//     F(c) = c / (b - a c)          [N],  c in [0, b/a)
// so 1/b is the stiffness at rest [N/mm] and b/a is where the spring bottoms out [mm] (the tissue
// between skin and bone is used up). Units: a [1/N], b [mm/N]. Templated on the scalar so Ceres
// can differentiate it.
#pragma once

namespace echosim::tissue {

template <class T>
T spring_force(const T& compression, const T& a, const T& b)
{
    return compression / (b - a * compression);
}

// Whether the spring can be compressed by `compression` at all: short of bottoming out, where
// spring_force is finite and positive. The fit asks it of trial parameters.
template <class T>
bool spring_holds(const T& compression, const T& a, const T& b)
{
    return b - a * compression > T(0);
}

// dF/dc = b / (b - a c)^2: the tangent stiffness the implicit integrator needs [N/mm].
template <class T>
T spring_stiffness(const T& compression, const T& a, const T& b)
{
    const T d = b - a * compression;
    return b / (d * d);
}

// The analytic inverse: the compression that produces force F, c = b F / (1 + a F).
template <class T>
T spring_compression(const T& force, const T& a, const T& b)
{
    return b * force / (T(1) + a * force);
}

// Compression at which the spring bottoms out [mm] (infinite for a = 0: a linear spring).
inline double spring_limit(double a, double b) { return a > 0 ? b / a : 1e300; }

}  // namespace echosim::tissue
