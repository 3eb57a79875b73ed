// The immutable parameters of the dynamics (paper §4), apart from the tissue model's own and from
// the mutable state; compiled with the tissue model into the CompiledModel (compiled_model.hpp).
// Units: mm, s, N, kg.
#pragma once

#include <Eigen/Core>

namespace echosim::physics {

enum class Integrator {
    implicit_euler,  // linearly implicit backward Euler, Baraff & Witkin 1998, solved by PCG
    explicit_euler,  // symplectic Euler, kept to show why the implicit one is needed
};

enum class JacobianMode {
    updated,   // the force Jacobian re-evaluated at every step
    constant,  // evaluated once at rest and reused (the paper's cheaper option)
};

struct PhysicsOptions {
    double time_step = 1e-3;  // [s]: 1 kHz
    // The physics publishes (its surface snapshot and local contact model, physics_runner.hpp) after
    // this many steps, reading the probe's latest command before each: its rate as its readers see
    // it. The paper's physics refreshed the haptic loop at about 100 Hz; the Fig. 8 demo makes that
    // 10 steps of 1 ms, since the 2,500-node patch's stiff penalty contact is not accurate at one
    // 10 ms step (a probe pressing at 20 mm/s meets 28 N where 7 N is right: bench/RESULTS.md).
    int steps_per_publish = 1;
    // Lock-step only (PhysicsRunner::step_to: exams, headless tools, tests): while nothing touches
    // the tissue and the probe's face stays stride_clearance_mm clear of the skin where it is and
    // where the step takes it, one step covers up to clear_stride time steps (never past the time
    // the caller steps to). A lifted probe carried between stations is half an exam's time, and
    // the tissue relaxing under it was stepped at 1 kHz for the contact's sake alone: the relaxation
    // is slow (its viscous tail, tenths of a second), which the implicit step follows as well at
    // 4 ms; nothing is pressed, so nothing an exam scores changes. The probe's sweep per step grows
    // with the stride (probe_sweep.hpp), and the clearance is checked at both ends of it. 1: off.
    // The real-time thread always steps time_step (its period is the wall clock's).
    int clear_stride = 4;
    double stride_clearance_mm = 2.0;
    Integrator integrator = Integrator::implicit_euler;
    JacobianMode jacobian = JacobianMode::updated;
    // the patient lies supine, so gravity points posterior: +y in LPS [mm/s^2]
    Eigen::Vector3d gravity{0.0, 9810.0, 0.0};
    // damping of the non-linear springs along the normal, as a fraction of critical damping of a
    // node's mass on its rest stiffness (the paper damps only the surface springs; without some
    // normal damping a node would ring on its spring for ever)
    double normal_damping_ratio = 0.7;
    // shear support of the tissue column under each node, as a fraction of the non-linear spring's
    // rest stiffness 1/b. The paper's springs act only along the normal and leave lateral stability
    // to the surface springs; with the fitted lambda as small as the data make it (about 6e-4 N/mm),
    // a node pushed in would slide sideways off its spring. Quasi-static pushes along the normal, all
    // the fit ever sees, do not feel it.
    double lateral_stiffness_ratio = 0.5;
    // relative residual at which conjugate gradient stops: 1e-4 gives the same probe force to four
    // digits as 1e-6 on the shipped model, with 40 % fewer iterations (bench/RESULTS.md)
    double cg_tolerance = 1e-4;
    // ... or when the force the solve leaves unbalanced, |b - A dv| / h over all nodes, is below
    // this [N], whatever |b| is. Tissue at rest, or settled under a probe held still, has a
    // right-hand side of round-off (1e-11 to 1e-8 N on the shipped patch) that the relative test
    // alone chases for ten iterations a step, half the physics thread's time. What the floor leaves
    // unbalanced keeps settled nodes trembling at about 2.5e3 mm/s per newton of it (2.5e-3 mm/s,
    // nanometres a step: under sleep_speed below, and far below anything a probe or an image
    // resolves).
    double cg_absolute_tolerance_N = 1e-6;
    int cg_max_iterations = 200;
    double max_speed = 5e4;  // [mm/s]: beyond this a node has exploded; the state is reset
    // Sleep, as Box2D's bodies do: tissue that has stayed still (no node faster than sleep_speed)
    // for sleep_after of simulated time, under a probe that has stayed still (no corner of its face
    // further than sleep_probe_mm from where it was, moving slower than sleep_speed) and an
    // external load that has not changed, is at rest: its velocities are zeroed and its steps only
    // advance the clock until the probe or the load moves. A trainee holds the probe still to read
    // the image far more than they move it; settled under the probe a step still costs the contact,
    // the forces and the Jacobian (a third of a core on the 2,500-node patch) to move nothing. Ten
    // micrometres a second (a micrometre over sleep_after) and a tenth of a micrometre are far
    // below anything an image or a hand resolves; a device's own noise keeps its tissue awake.
    // Tissue still with nothing touching it sleeps wherever the probe goes as long as it stays clear
    // of the skin (a lifted probe carried between stations; each such step runs the contact test
    // alone, and wakes the tissue at the first touch). sleep_after = 0 turns sleeping off.
    double sleep_speed = 1e-2;      // [mm/s]
    double sleep_probe_mm = 1e-4;   // [mm]
    double sleep_after = 0.1;       // [s]
    // threads that share a step's sweeps (the physics thread and threads - 1 more, which spin
    // between the step's passes). One is right where the physics thread must leave the other
    // cores to rendering and haptics; more pay off on large patches (bench/RESULTS.md), never more
    // than there are free cores. The team belongs to whoever steps (PhysicsRunner, Simulation) and has
    // this many parts; a state's buffers are sized for it. Results repeat bit for bit for a given
    // count; between counts they agree to the CG tolerance.
    int threads = 1;
};

}  // namespace echosim::physics
