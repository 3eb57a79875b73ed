#include "io/transform_repository.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <deque>
#include <map>
#include <set>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace echosim::io {
namespace {

std::string join(const std::vector<std::string>& names)
{
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

}  // namespace

std::optional<std::pair<std::string, std::string>> split_transform_name(std::string_view name)
{
    std::optional<std::size_t> at;
    for (std::size_t i = 1; i + 2 < name.size(); ++i)
        if (name.substr(i, 2) == "To" && std::isupper(static_cast<unsigned char>(name[i + 2]))) {
            if (at) return std::nullopt;  // ambiguous
            at = i;
        }
    if (!at) return std::nullopt;
    return std::pair{std::string(name.substr(0, *at)), std::string(name.substr(*at + 2))};
}

bool all_finite(const glm::dmat4& m)
{
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

bool is_affine(const glm::dmat4& m) { return m[0][3] == 0 && m[1][3] == 0 && m[2][3] == 0 && m[3][3] == 1; }

namespace {

// [1] below this, a column's length beside the longest, or the sine of the angle it makes with the
// others' plane, is taken for none: a spacing a million times finer than its neighbour is no image
constexpr double kFlat = 1e-6;

}  // namespace

bool is_singular(const glm::dmat4& m)
{
    const glm::dvec3 a(m[0]), b(m[1]), c(m[2]);
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double longest = std::max({la, lb, lc});
    if (!(longest > 0) || std::min({la, lb, lc}) < kFlat * longest) return true;
    return std::abs(glm::determinant(glm::dmat3(m))) < kFlat * la * lb * lc;
}

bool flattens_plane(const glm::dmat4& m)
{
    const glm::dvec3 a(m[0]), b(m[1]);
    const double la = glm::length(a), lb = glm::length(b);
    if (!(std::max(la, lb) > 0) || std::min(la, lb) < kFlat * std::max(la, lb)) return true;
    return glm::length(glm::cross(a, b)) < kFlat * la * lb;
}

TransformRepository::Key TransformRepository::key(std::string_view a, std::string_view b)
{
    return a < b ? Key{std::string(a), std::string(b)} : Key{std::string(b), std::string(a)};
}

void TransformRepository::set(const std::string& from, const std::string& to, const glm::dmat4& matrix, bool valid)
{
    if (from.empty() || to.empty()) throw TransformError("a transform needs both a 'from' and a 'to' frame name");
    if (from == to) throw TransformError(from + "To" + to + ": a transform from a frame to itself");
    if (!all_finite(matrix)) throw TransformError(from + "To" + to + ": the matrix is not finite");
    if (!is_affine(matrix))
        throw TransformError(from + "To" + to + ": the last row is not 0 0 0 1: not an affine transform");
    const auto [at, added] = index_.try_emplace(key(from, to), links_.size());
    if (!added) {
        links_[at->second] = Link{from, to, {matrix, valid}};  // either way round: one answer only
        return;
    }
    links_.push_back(Link{from, to, {matrix, valid}});
    touching_[from].push_back(at->second);
    touching_[to].push_back(at->second);
}

const FrameTransform* TransformRepository::held(std::string_view from, std::string_view to, bool* forward) const
{
    const auto it = index_.find(key(from, to));
    if (it == index_.end()) return nullptr;
    const Link& l = links_[it->second];
    if (forward) *forward = l.from == from;
    return &l.transform;
}

std::optional<std::vector<TransformRepository::Step>> TransformRepository::chain(std::string_view from, std::string_view to) const
{
    if (from == to) return std::vector<Step>{};
    // breadth first from `from`: the shortest chain, so a direct transform always wins
    struct CameBy {
        std::size_t link;
        bool forward;
    };
    std::map<std::string, std::optional<CameBy>, std::less<>> came_by{{std::string(from), std::nullopt}};
    std::deque<std::string> queue{std::string(from)};
    while (!queue.empty() && !came_by.contains(to)) {
        const std::string frame = queue.front();
        queue.pop_front();
        const auto links = touching_.find(frame);
        if (links == touching_.end()) continue;
        for (const std::size_t i : links->second) {
            const Link& l = links_[i];
            const std::string& next = l.from == frame ? l.to : l.from;
            if (came_by.contains(next)) continue;
            came_by.emplace(next, CameBy{i, l.from == frame});
            queue.push_back(next);
        }
    }
    if (!came_by.contains(to)) return std::nullopt;
    // walk back from `to`: the steps, last first, then turned round
    std::vector<Step> steps;
    std::string frame(to);
    while (const auto step = came_by.find(frame)->second) {
        const Link& l = links_[step->link];
        steps.push_back(Step{l.from, l.to, step->forward});
        frame = step->forward ? l.from : l.to;
    }
    std::reverse(steps.begin(), steps.end());
    return steps;
}

FrameTransform TransformRepository::product(const std::vector<Step>& chain) const
{
    FrameTransform out;
    for (std::size_t s = 0; s < chain.size(); ++s) {
        const Step& step = chain[s];
        bool as_held = true;  // the link may have been set the other way round since the chain was found
        const FrameTransform* t = held(step.from, step.to, &as_held);
        if (!t) throw TransformError(step.from + "To" + step.to + ": not held (a chain kept past a change of transforms)");
        const bool forward = step.forward == as_held;
        const std::string& from = as_held ? step.from : step.to;
        const std::string& to = as_held ? step.to : step.from;
        const std::string name = from + "To" + to;  // as held
        glm::dmat4 m = t->matrix;
        // a transform the tracker marked invalid is not used, whatever its matrix
        if (t->valid) {
            if (!forward && is_singular(m))
                throw TransformError(name + " is singular: it cannot be inverted to give " + to + "To" + from);
            if (forward && s > 0 && is_singular(m))
                throw TransformError(name + " is singular (it flattens space onto a plane, a line or a point): a chain of "
                                            "motions cannot pass through it");
            if (forward && s == 0 && flattens_plane(m))
                throw TransformError(name + " is singular: it maps the " + from + " frame's x-y plane onto a line or a "
                                            "point (pixel steps of no length, or parallel)");
        }
        // an invalid link's matrix only has to stand in: the chain is marked invalid and not used
        if (!forward) m = is_singular(m) ? glm::dmat4(1.0) : glm::inverse(m);
        out.matrix = m * out.matrix;  // link_n * ... * link_1: the first link applies first
        out.valid = out.valid && t->valid;
    }
    return out;
}

std::optional<FrameTransform> TransformRepository::find(std::string_view from, std::string_view to) const
{
    const auto steps = chain(from, to);
    if (!steps) return std::nullopt;
    return product(*steps);
}

std::vector<std::string> TransformRepository::reachable(std::string_view frame) const
{
    std::vector<std::string> seen{std::string(frame)};
    std::set<std::string, std::less<>> known{std::string(frame)};
    for (std::size_t n = 0; n < seen.size(); ++n) {
        const auto links = touching_.find(seen[n]);
        if (links == touching_.end()) continue;
        for (const std::size_t i : links->second) {
            const Link& l = links_[i];
            const std::string& next = l.from == seen[n] ? l.to : l.from;
            if (known.insert(next).second) seen.push_back(next);
        }
    }
    return seen;
}

FrameTransform TransformRepository::get(std::string_view from, std::string_view to) const
{
    if (auto t = find(from, to)) return *t;
    const std::vector<std::string> a = reachable(from), b = reachable(to);
    std::string why = "no chain of transforms from " + std::string(from) + " to " + std::string(to) + ": " +
                      std::string(from) + " reaches {" + join(a) + "}, " + std::string(to) + " reaches {" + join(b) +
                      "}; missing: a transform from one of the first to one of the second, e.g. " + a.back() + "To" + b.back();
    why += links_.empty() ? " (no transforms are known)" : " (known: " + join(names()) + ")";
    throw TransformError(why);
}

bool TransformRepository::knows(std::string_view frame) const { return touching_.contains(frame); }

std::vector<std::string> TransformRepository::names() const
{
    std::vector<std::string> out;
    out.reserve(links_.size());
    for (const Link& l : links_) out.push_back(l.from + "To" + l.to);
    return out;
}

}  // namespace echosim::io
