#include "io/transform_repository.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <deque>
#include <map>

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

void TransformRepository::set(const std::string& from, const std::string& to, const glm::dmat4& matrix, bool valid)
{
    if (from.empty() || to.empty()) throw TransformError("a transform needs both a 'from' and a 'to' frame name");
    if (from == to) throw TransformError(from + "To" + to + ": a transform from a frame to itself");
    if (!all_finite(matrix)) throw TransformError(from + "To" + to + ": the matrix is not finite");
    if (!is_affine(matrix))
        throw TransformError(from + "To" + to + ": the last row is not 0 0 0 1: not an affine transform");
    for (Link& l : links_)
        if ((l.from == from && l.to == to) || (l.from == to && l.to == from)) {
            l = Link{from, to, {matrix, valid}};
            return;
        }
    links_.push_back(Link{from, to, {matrix, valid}});
}

std::optional<FrameTransform> TransformRepository::find(std::string_view from, std::string_view to) const
{
    if (from == to) return FrameTransform{};
    // breadth first from `from`: the shortest chain, so a direct transform always wins
    struct Step {
        std::size_t link;
        bool forward;
    };
    std::map<std::string, std::optional<Step>, std::less<>> came_by{{std::string(from), std::nullopt}};
    std::deque<std::string> queue{std::string(from)};
    while (!queue.empty() && !came_by.contains(to)) {
        const std::string frame = queue.front();
        queue.pop_front();
        for (std::size_t i = 0; i < links_.size(); ++i) {
            const Link& l = links_[i];
            const std::string* next = l.from == frame ? &l.to : l.to == frame ? &l.from : nullptr;
            if (!next || came_by.contains(*next)) continue;
            came_by.emplace(*next, Step{i, l.from == frame});
            queue.push_back(*next);
        }
    }
    if (!came_by.contains(to)) return std::nullopt;

    // walk back from `to`, multiplying on the right: result = link_n * ... * link_1
    FrameTransform out;
    std::string frame(to);
    while (const auto step = came_by.find(frame)->second) {
        const Link& l = links_[step->link];
        glm::dmat4 m = l.transform.matrix;
        if (!step->forward) {
            if (std::abs(glm::determinant(glm::dmat3(m))) < 1e-12)
                throw TransformError(l.from + "To" + l.to + " is singular: it cannot be inverted to give " + l.to + "To" + l.from);
            m = glm::inverse(m);
        }
        out.matrix = out.matrix * m;
        out.valid = out.valid && l.transform.valid;
        frame = step->forward ? l.from : l.to;
    }
    return out;
}

std::vector<std::string> TransformRepository::reachable(std::string_view frame) const
{
    std::vector<std::string> seen{std::string(frame)};
    for (std::size_t n = 0; n < seen.size(); ++n)
        for (const Link& l : links_) {
            const std::string* next = l.from == seen[n] ? &l.to : l.to == seen[n] ? &l.from : nullptr;
            if (next && std::find(seen.begin(), seen.end(), *next) == seen.end()) seen.push_back(*next);
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

bool TransformRepository::knows(std::string_view frame) const
{
    return std::any_of(links_.begin(), links_.end(), [&](const Link& l) { return l.from == frame || l.to == frame; });
}

std::vector<std::string> TransformRepository::names() const
{
    std::vector<std::string> out;
    out.reserve(links_.size());
    for (const Link& l : links_) out.push_back(l.from + "To" + l.to);
    return out;
}

}  // namespace echosim::io
