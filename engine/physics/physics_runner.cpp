#include "physics/physics_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "physics/probe_sweep.hpp"

namespace echosim::physics {
namespace {

SurfaceSnapshot prototype(const CompiledModel& model)
{
    SurfaceSnapshot s;
    s.positions.resize(std::size_t(model.rest.size()));
    for (Eigen::Index i = 0; i < model.rest.size(); ++i) s.positions[std::size_t(i)] = float(model.rest[i]);
    return s;
}

const std::shared_ptr<const CompiledModel>& checked(const std::shared_ptr<const CompiledModel>& model)
{
    if (!model) throw std::invalid_argument("PhysicsRunner: no compiled model");
    if (model->options.steps_per_publish < 1)
        throw std::invalid_argument("PhysicsRunner: steps_per_publish " + std::to_string(model->options.steps_per_publish) + ": must be >= 1");
    return model;
}

}  // namespace

PhysicsRunner::PhysicsRunner(const tissue::TissueModel& model, const PhysicsOptions& options)
    : PhysicsRunner(compile_model(model, options))
{
}

PhysicsRunner::PhysicsRunner(std::shared_ptr<const CompiledModel> model)
    : model_(checked(model)), state_(make_state(*model_)), team_(model_->options.threads), out_(prototype(*model_))
{
}

PhysicsRunner::~PhysicsRunner() { stop(); }

std::string probe_command_error(const ProbeCommand& c)
{
    if (!c.position.allFinite()) return "position is not finite";
    if (!c.orientation.coeffs().allFinite()) return "orientation is not finite";
    if (std::abs(c.orientation.norm() - 1.0) > 1e-3) return "orientation is not a rotation (quaternion norm " + std::to_string(c.orientation.norm()) + ")";
    if (!c.velocity.allFinite()) return "velocity is not finite";
    return {};
}

bool PhysicsRunner::command(const ProbeCommand& c)
{
    if (!probe_command_error(c).empty()) {
        refused_.fetch_add(1, std::memory_order_relaxed);
        return false;
    }
    in_.write_slot() = c;
    in_.publish();
    return true;
}

void PhysicsRunner::step_once(int stride)
{
    const double h = model_->options.time_step * stride;
    for (int i = 0; i < model_->options.steps_per_publish; ++i) {
        state_.probe = swept_probe(state_.probe, in_.read(), h, stride * kMaxProbeMoveMm);
        step(*model_, state_, team_, stride);
        if (state_.last.asleep) asleep_.fetch_add(stride, std::memory_order_relaxed);
    }

    SurfaceSnapshot& s = out_.write_slot();
    s.time = state_.time;
    s.step = state_.steps;
    for (Eigen::Index i = 0; i < state_.x.size(); ++i) s.positions[std::size_t(i)] = float(state_.x[i]);
    s.probe_force_N = state_.last.probe_force_N;
    s.contacts = state_.last.contacts;
    s.cg_iterations = state_.last.cg_iterations;
    s.resets = state_.resets;
    out_.publish();
    contact_out_.write_slot() = local_contact_model(*model_, state_);
    contact_out_.publish();
    steps_.fetch_add(stride, std::memory_order_relaxed);
    if (stride > 1) strides_.fetch_add(1, std::memory_order_relaxed);
    if (after_step_) after_step_(state_.steps);
}

void PhysicsRunner::step_to(double t) { step_to(t, t); }

void PhysicsRunner::step_to(double t, double horizon)
{
    if (running_) throw std::logic_error("PhysicsRunner::step_to while the physics thread runs");
    const double period = model_->options.time_step * model_->options.steps_per_publish;
    const double until = std::max(t, horizon);
    while (state_.time + 0.5 * period < t) step_once(stride_before(until));
}

int PhysicsRunner::stride_before(double until)
{
    const PhysicsOptions& o = model_->options;
    // whole time steps left (rounded as step_to rounds: a step may end half a step past)
    const double room = std::floor((until - state_.time) / o.time_step + 0.5);
    const int most = int(std::clamp(room, 1.0, double(std::max(1, o.clear_stride))));
    if (most == 1 || o.steps_per_publish != 1 || state_.last.contacts != 0) return 1;
    const contact::ProbeState next = swept_probe(state_.probe, in_.read(), most * o.time_step, most * kMaxProbeMoveMm);
    const bool clear = probe_clear_by(model_->probe, state_.probe, state_.x, o.stride_clearance_mm) &&
                       probe_clear_by(model_->probe, next, state_.x, o.stride_clearance_mm);
    return clear ? most : 1;
}

void PhysicsRunner::replace_model(std::shared_ptr<const CompiledModel> model)
{
    checked(model);
    TissueState rest = make_state(*model);
    replace_model(std::move(model), std::move(rest));
}

void PhysicsRunner::replace_model(std::shared_ptr<const CompiledModel> model, TissueState rest)
{
    if (running_) throw std::logic_error("PhysicsRunner::replace_model while the physics thread runs");
    checked(model);
    if (rest.x.size() != Eigen::Index(3 * model->node_count()) || rest.node_scratch.size() != model->node_count())
        throw std::invalid_argument("PhysicsRunner::replace_model: a state of " + std::to_string(rest.x.size() / 3) + " nodes for a model of " +
                                    std::to_string(model->node_count()));
    if (model->node_count() != model_->node_count())
        throw std::invalid_argument("PhysicsRunner::replace_model: " + std::to_string(model->node_count()) + " nodes, the runner steps " +
                                    std::to_string(model_->node_count()) + " (its snapshots are sized for them)");
    if (model->options.threads != model_->options.threads)
        throw std::invalid_argument("PhysicsRunner::replace_model: " + std::to_string(model->options.threads) + " threads, the runner's team has " +
                                    std::to_string(model_->options.threads));
    TissueState next = std::move(rest);
    next.time = state_.time;
    next.steps = state_.steps;
    next.resets = state_.resets;
    next.probe = state_.probe;
    model_ = std::move(model);
    state_ = std::move(next);
    // no thread steps: this thread is the snapshots' writer until the next step (start() or
    // step_to hands that role back, with the ordering a thread's start gives)
    SurfaceSnapshot& s = out_.write_slot();
    s.time = state_.time;
    s.step = state_.steps;
    for (Eigen::Index i = 0; i < state_.x.size(); ++i) s.positions[std::size_t(i)] = float(state_.x[i]);
    s.probe_force_N = 0;
    s.contacts = 0;
    s.cg_iterations = 0;
    s.resets = state_.resets;
    out_.publish();
    LocalContactModel& c = contact_out_.write_slot();
    c = LocalContactModel{};
    c.time = state_.time;
    c.step = state_.steps;
    contact_out_.publish();
}

void PhysicsRunner::start()
{
    if (running_.exchange(true)) return;
    thread_ = std::thread([this] {
        using clock = std::chrono::steady_clock;
        const auto period = std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(model_->options.time_step * model_->options.steps_per_publish));
        auto due = clock::now();
        while (running_.load(std::memory_order_relaxed)) {
            step_once();
            due += period;
            const auto now = clock::now();
            if (now > due + period) {
                // fell behind by more than a step: count it and do not try to catch up in a burst
                overruns_.fetch_add(1, std::memory_order_relaxed);
                due = now;
            }
            std::this_thread::sleep_until(due);
        }
    });
}

void PhysicsRunner::stop()
{
    if (!running_.exchange(false)) return;
    if (thread_.joinable()) thread_.join();
}

}  // namespace echosim::physics
