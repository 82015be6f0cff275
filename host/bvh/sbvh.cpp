// Spatial-split BVH builder (see sbvh.h). Top-down with an explicit task stack; each task owns its
// references (a box and a shape index); subtrees go to other threads while threads are free, and
// the tree is the same node for node whatever the thread count (as build.cpp). Per node: the binned object split of
// build.cpp over the references' box centres; where its two boxes overlap, also the binned
// spatial split (Stich et al. 2009, sec. 4.2-4.3: each reference clipped into every bin it
// crosses, counted as entering its first bin and leaving its last); the cheaper by the SAH wins,
// and a spatial split puts a crossing reference wholly on one side where that is cheaper than
// cutting it (reference unsplitting, sec. 4.5).
#include "bvh/sbvh.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <future>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace vkp {

namespace {

constexpr std::uint32_t kMaxBins = 256;
constexpr float kInf = std::numeric_limits<float>::infinity();
/// Nodes of at most this many references evaluate the object SAH exactly (build.cpp's kSweepMax).
constexpr std::size_t kSweepMax = 16;

Aabb intersect(const Aabb& a, const Aabb& b) {
    Aabb r;
    r.lo = glm::max(a.lo, b.lo);
    r.hi = glm::min(a.hi, b.hi);
    return r;
}

Aabb unite(Aabb a, const Aabb& b) {
    a.grow(b);
    return a;
}

glm::vec3 centre(const Aabb& b) { return 0.5f * (b.lo + b.hi); }

/// b widened by 4 ulps of its largest coordinate magnitude on every side.
Aabb widen(const Aabb& b) {
    const glm::vec3 m = glm::max(glm::abs(b.lo), glm::abs(b.hi));
    const glm::vec3 e = m * (4.0f * std::numeric_limits<float>::epsilon()) + std::numeric_limits<float>::min();
    Aabb r;
    r.lo = b.lo - e;
    r.hi = b.hi + e;
    return r;
}

struct Ref {
    Aabb box;
    std::uint32_t id;
};

struct Task {
    std::uint32_t node, depth;
    std::vector<Ref> refs;
    std::size_t extra;  // references this subtree may add by spatial splits
    int fork = -1;      // >= 0: the subtree of `node` is built by SbvhBuilder::forks_[fork]; splice it
};

/// A subtree built on its own: nodes[0] is its root; inner nodes' child indices count from 0,
/// leaves' primitive ranges index its own prims.
struct Subtree {
    std::vector<BvhBuildNode> nodes;
    std::vector<std::uint32_t> prims;
    std::uint32_t maxDepth = 0;
};

/// Subtrees of at least this many references may go to another thread (build.cpp's kForkMin).
constexpr std::size_t kForkMin = 4096;

struct ObjectSplit {
    int axis = -1;
    std::uint32_t bin = 0;  // left: centre bins [0, bin)
    float cost = kInf;      // A_L N_L + A_R N_R
    float lo = 0.0f, scale = 0.0f;
    Aabb left, right;
};

struct SpatialSplit {
    int axis = -1;
    float pos = 0.0f;
    float cost = kInf;
    std::uint32_t added = 0;  // references the split adds (N_L + N_R - N), before unsplitting
};

/// The best boundary of one axis's row of nb bins by the SAH: the left side is bins [0, k), with
/// the references counted in `enter`, the right side bins [k, nb), counted in `leave` (object
/// bins: both their counts; spatial slabs: where references enter and where they leave).
struct BinSweep {
    std::uint32_t bin = 0;
    float cost = kInf;  // A_L N_L + A_R N_R
    Aabb left, right;
    std::uint32_t nLeft = 0, nRight = 0;
};
BinSweep sweepBins(const Aabb* boxes, const std::uint32_t* enter, const std::uint32_t* leave, std::uint32_t nb) {
    Aabb rightBox[kMaxBins];
    std::uint32_t rightCount[kMaxBins] = {};
    Aabb acc;
    std::uint32_t cnt = 0;
    for (std::uint32_t k = nb - 1; k > 0; --k) {
        acc.grow(boxes[k]);
        cnt += leave[k];
        rightBox[k] = acc;
        rightCount[k] = cnt;
    }
    BinSweep best;
    acc = Aabb{};
    cnt = 0;
    for (std::uint32_t k = 1; k < nb; ++k) {
        acc.grow(boxes[k - 1]);
        cnt += enter[k - 1];
        if (cnt == 0 || rightCount[k] == 0) continue;
        const float cost = acc.halfArea() * static_cast<float>(cnt) + rightBox[k].halfArea() * static_cast<float>(rightCount[k]);
        if (cost < best.cost) best = {k, cost, acc, rightBox[k], cnt, rightCount[k]};
    }
    return best;
}

class SbvhBuilder {
public:
    /// rootArea: the whole tree's root box's half area (alpha's unit); freeThreads: threads that
    /// may still be started.
    SbvhBuilder(std::span<const Shape> shapes, const SbvhOptions& opt, float rootArea, std::atomic<int>& freeThreads)
        : shapes_(shapes), opt_(opt), rootArea_(rootArea), freeThreads_(freeThreads) {}

    /// Builds the subtree of `root` (root.node is ignored) whose root node, box set, is rootNode.
    Subtree build(Task root, const BvhBuildNode& rootNode) {
        Subtree out;
        nodes_ = &out.nodes;
        prims_ = &out.prims;
        out.nodes.push_back(rootNode);
        out.maxDepth = root.depth;
        root.node = 0;
        root.fork = -1;
        std::vector<Task> stack;
        stack.push_back(std::move(root));
        while (!stack.empty()) {
            Task t = std::move(stack.back());
            stack.pop_back();
            if (t.fork >= 0) splice(t, out.maxDepth);
            else process(std::move(t), stack, out.maxDepth);
        }
        return out;
    }

private:
    /// Appends the forked subtree of marker t after the nodes and primitives built so far; its root
    /// replaces node t.node. The same nodes, in the same order, as a build on one thread.
    void splice(const Task& t, std::uint32_t& maxDepth) {
        Subtree sub = forks_[static_cast<std::size_t>(t.fork)].get();
        const auto nodeOffset = static_cast<std::uint32_t>(nodes_->size() - 1);  // its node i (i >= 1) goes to nodeOffset + i
        const auto primOffset = static_cast<std::uint32_t>(prims_->size());
        auto moved = [&](BvhBuildNode n) {
            n.index += n.isLeaf() ? primOffset : nodeOffset;
            return n;
        };
        (*nodes_)[t.node] = moved(sub.nodes[0]);
        for (std::size_t i = 1; i < sub.nodes.size(); ++i) nodes_->push_back(moved(sub.nodes[i]));
        prims_->insert(prims_->end(), sub.prims.begin(), sub.prims.end());
        maxDepth = std::max(maxDepth, sub.maxDepth);
    }

    void makeLeaf(const Task& t, std::uint32_t& maxDepth) {
        BvhBuildNode& node = (*nodes_)[t.node];
        node.index = static_cast<std::uint32_t>(prims_->size());
        node.count = static_cast<std::uint32_t>(t.refs.size());
        for (const Ref& r : t.refs) prims_->push_back(r.id);
        maxDepth = std::max(maxDepth, t.depth);
    }

    void process(Task t, std::vector<Task>& stack, std::uint32_t& maxDepth) {
        const std::size_t n = t.refs.size();
        const auto& base = opt_.base;
        const bool mustSplit = n > base.maxLeafSize || (t.depth == 0 && n >= 2);
        if (n == 1) return makeLeaf(t, maxDepth);
        const bool sahAllowed = levelsNeeded(n, base.maxLeafSize) < base.maxDepth - t.depth;
        const float area = (*nodes_)[t.node].box.halfArea();

        std::vector<Ref> left, right;
        bool split = false;
        if (sahAllowed) {
            const ObjectSplit obj = findObjectSplit(t.refs);
            SpatialSplit sp;
            const float overlap = obj.axis >= 0 ? intersect(obj.left, obj.right).halfArea() : kInf;
            if (overlap > opt_.alpha * rootArea_ && t.extra > 0) sp = findSpatialSplit(t.refs, (*nodes_)[t.node].box);
            if (sp.added > t.extra) sp = SpatialSplit{};  // over this subtree's budget
            const float best = std::min(obj.cost, sp.cost);
            const float ct = base.traversalCost, ci = base.intersectionCost;
            // Ct + Ci * cost / A < Ci * n, multiplied by A (A may be 0 for collinear points).
            const bool sahWins = best < kInf && ct * area + ci * best < ci * static_cast<float>(n) * area;
            if (!sahWins && !mustSplit) return makeLeaf(t, maxDepth);
            if (sp.cost < obj.cost) split = spatialPartition(t.refs, sp, left, right);
            if (!split && obj.axis >= 0) {
                partitionObject(t.refs, obj, left, right);
                split = true;
            }
        } else if (!mustSplit) {
            return makeLeaf(t, maxDepth);
        }
        if (!split) medianSplit(t.refs, left, right);
        // What is left of the budget goes to the children in proportion to their references (as
        // Embree shares its split budget), so the first subtrees built cannot spend it all.
        const std::size_t added = left.size() + right.size() - n, rest = t.extra - std::min(t.extra, added);
        const auto leftExtra = static_cast<std::size_t>(double(rest) * double(left.size()) / double(left.size() + right.size()));
        t.refs.clear();
        t.refs.shrink_to_fit();

        const auto first = static_cast<std::uint32_t>(nodes_->size());
        (*nodes_)[t.node].index = first;
        (*nodes_)[t.node].count = 0;
        BvhBuildNode l, r;
        for (const Ref& x : left) l.box.grow(x.box);
        for (const Ref& x : right) r.box.grow(x.box);
        nodes_->push_back(l);
        nodes_->push_back(r);
        // Right pushed first: the left subtree is built (and its leaves numbered) first.
        Task rightTask{first + 1, t.depth + 1, std::move(right), rest - leftExtra};
        if (rightTask.refs.size() >= kForkMin && takeThread(freeThreads_)) {
            // The right subtree on another thread; the marker left in its place splices it in once
            // the left subtree is done, where the sequential build would have put it.
            const int fork = static_cast<int>(forks_.size());
            forks_.push_back(std::async(std::launch::async, [this, task = std::move(rightTask), r]() mutable {
                SbvhBuilder other(shapes_, opt_, rootArea_, freeThreads_);
                Subtree sub = other.build(std::move(task), r);
                freeThreads_.fetch_add(1);
                return sub;
            }));
            rightTask = Task{first + 1, t.depth + 1, {}, 0, fork};
        }
        stack.push_back(std::move(rightTask));
        stack.push_back({first, t.depth + 1, std::move(left), leftExtra});
    }

    std::uint32_t bin(float c, float lo, float scale) const {
        const float f = (c - lo) * scale;
        const auto last = static_cast<float>(opt_.base.binCount - 1);
        return f > 0.0f ? static_cast<std::uint32_t>(std::min(f, last)) : 0u;
    }

    /// Exact SAH for a small node, as build.cpp's sweep: per axis, the references sorted by box
    /// centre and every split position evaluated. bin = the number of references on the left of
    /// the sorted order (which partitionObject re-creates).
    ObjectSplit findSweepSplit(const std::vector<Ref>& refs) const {
        const std::size_t n = refs.size();
        ObjectSplit best;
        std::vector<std::uint32_t> order(n);
        std::vector<float> rightCost(n);
        std::vector<Aabb> rightBox(n);
        for (int a = 0; a < 3; ++a) {
            for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
            std::stable_sort(order.begin(), order.end(),
                             [&](std::uint32_t x, std::uint32_t y) { return centre(refs[x].box)[a] < centre(refs[y].box)[a]; });
            Aabb acc;
            for (std::size_t k = n - 1; k > 0; --k) {
                acc.grow(refs[order[k]].box);
                rightBox[k] = acc;
                rightCost[k] = acc.halfArea() * static_cast<float>(n - k);
            }
            acc = Aabb{};
            for (std::size_t k = 1; k < n; ++k) {
                acc.grow(refs[order[k - 1]].box);
                const float cost = acc.halfArea() * static_cast<float>(k) + rightCost[k];
                if (cost < best.cost) {
                    best.axis = a;
                    best.bin = static_cast<std::uint32_t>(k);
                    best.cost = cost;
                    best.scale = 0.0f;  // marks a sweep split
                    best.left = acc;
                    best.right = rightBox[k];
                }
            }
        }
        return best;
    }

    /// Splits refs by an object split (binned or swept).
    void partitionObject(std::vector<Ref>& refs, const ObjectSplit& obj, std::vector<Ref>& left, std::vector<Ref>& right) const {
        if (obj.scale == 0.0f) {
            const int a = obj.axis;
            std::stable_sort(refs.begin(), refs.end(), [a](const Ref& x, const Ref& y) { return centre(x.box)[a] < centre(y.box)[a]; });
            left.assign(refs.begin(), refs.begin() + obj.bin);
            right.assign(refs.begin() + obj.bin, refs.end());
            return;
        }
        for (const Ref& r : refs) (bin(centre(r.box)[obj.axis], obj.lo, obj.scale) < obj.bin ? left : right).push_back(r);
    }

    /// build.cpp's binned SAH over the references' box centres (its sweep for small nodes).
    ObjectSplit findObjectSplit(const std::vector<Ref>& refs) const {
        if (refs.size() <= kSweepMax) return findSweepSplit(refs);
        Aabb cbox;
        for (const Ref& r : refs) cbox.grow(centre(r.box));
        const std::uint32_t nb = opt_.base.binCount;
        ObjectSplit best;
        for (int a = 0; a < 3; ++a) {
            const float extent = cbox.hi[a] - cbox.lo[a];
            const float scale = static_cast<float>(nb) / extent;
            if (!(extent > 0.0f) || !std::isfinite(scale)) continue;
            Aabb boxes[kMaxBins];
            std::uint32_t counts[kMaxBins] = {};
            for (const Ref& r : refs) {
                const std::uint32_t k = bin(centre(r.box)[a], cbox.lo[a], scale);
                boxes[k].grow(r.box);
                ++counts[k];
            }
            const BinSweep sw = sweepBins(boxes, counts, counts, nb);
            if (sw.cost < best.cost) {
                best.axis = a;
                best.bin = sw.bin;
                best.cost = sw.cost;
                best.lo = cbox.lo[a];
                best.scale = scale;
                best.left = sw.left;
                best.right = sw.right;
            }
        }
        return best;
    }

    /// The binned spatial split: per axis, spatialBins slabs of the node's box; each reference cut
    /// into the slabs it crosses (splitReference), its parts growing their slabs' boxes.
    SpatialSplit findSpatialSplit(const std::vector<Ref>& refs, const Aabb& nodeBox) const {
        const std::uint32_t nb = opt_.spatialBins;
        SpatialSplit best;
        for (int a = 0; a < 3; ++a) {
            const float lo = nodeBox.lo[a], width = (nodeBox.hi[a] - lo) / static_cast<float>(nb);
            if (!(width > 0.0f) || !std::isfinite(width)) continue;
            auto slab = [&](float x) {
                const float f = (x - lo) / width;
                return f > 0.0f ? static_cast<std::uint32_t>(std::min(f, static_cast<float>(nb - 1))) : 0u;
            };
            Aabb boxes[kMaxBins];
            std::uint32_t entry[kMaxBins] = {}, exit[kMaxBins] = {};
            for (const Ref& r : refs) {
                const std::uint32_t b0 = slab(r.box.lo[a]), b1 = slab(r.box.hi[a]);
                ++entry[b0];
                ++exit[b1];
                Aabb rest = r.box;
                for (std::uint32_t k = b0; k < b1 && !rest.empty(); ++k) {
                    Aabb part, next;
                    splitReference(shapes_[r.id], rest, a, lo + static_cast<float>(k + 1) * width, part, next);
                    boxes[k].grow(part);
                    rest = next;
                }
                boxes[b1].grow(rest);
            }
            const BinSweep sw = sweepBins(boxes, entry, exit, nb);
            if (sw.cost < best.cost) {
                best.axis = a;
                best.pos = lo + static_cast<float>(sw.bin) * width;
                best.cost = sw.cost;
                best.added = static_cast<std::uint32_t>(sw.nLeft + sw.nRight - refs.size());
            }
        }
        return best;
    }

    /// Performs a spatial split; false (left and right untouched) when a side would be empty.
    /// A side may keep every reference (all cut): its box is smaller, the duplication budget
    /// bounds how often that happens, and the depth budget is checked per node.
    bool spatialPartition(const std::vector<Ref>& refs, const SpatialSplit& sp, std::vector<Ref>& left,
                          std::vector<Ref>& right) const {
        const int a = sp.axis;
        struct Cut {
            Ref whole;
            Aabb l, r;
        };
        std::vector<Cut> cuts;
        Aabb lbox, rbox;
        std::vector<Ref> l, r;
        for (const Ref& ref : refs) {
            if (ref.box.hi[a] <= sp.pos) {
                l.push_back(ref);
                lbox.grow(ref.box);
            } else if (ref.box.lo[a] >= sp.pos) {
                r.push_back(ref);
                rbox.grow(ref.box);
            } else {
                Cut c{ref, {}, {}};
                splitReference(shapes_[ref.id], ref.box, a, sp.pos, c.l, c.r);
                if (c.l.empty()) {
                    r.push_back({c.r, ref.id});
                    rbox.grow(c.r);
                } else if (c.r.empty()) {
                    l.push_back({c.l, ref.id});
                    lbox.grow(c.l);
                } else {
                    lbox.grow(c.l);
                    rbox.grow(c.r);
                    cuts.push_back(c);
                }
            }
        }
        // Reference unsplitting (Stich et al. sec. 4.5): a cut reference goes wholly to one side
        // where that costs less than having a part on each.
        float nl = static_cast<float>(l.size() + cuts.size()), nr = static_cast<float>(r.size() + cuts.size());
        for (const Cut& c : cuts) {
            const float both = lbox.halfArea() * nl + rbox.halfArea() * nr;
            const Aabb l1 = unite(lbox, c.whole.box), r2 = unite(rbox, c.whole.box);
            const float toLeft = l1.halfArea() * nl + rbox.halfArea() * (nr - 1.0f);
            const float toRight = lbox.halfArea() * (nl - 1.0f) + r2.halfArea() * nr;
            if (toLeft < both && toLeft <= toRight) {
                l.push_back(c.whole);
                lbox = l1;
                nr -= 1.0f;
            } else if (toRight < both) {
                r.push_back(c.whole);
                rbox = r2;
                nl -= 1.0f;
            } else {
                l.push_back({c.l, c.whole.id});
                r.push_back({c.r, c.whole.id});
            }
        }
        if (l.empty() || r.empty()) return false;
        left = std::move(l);
        right = std::move(r);
        return true;
    }

    /// Object median on the axis of largest centre extent (the middle index when all coincide).
    static void medianSplit(std::vector<Ref>& refs, std::vector<Ref>& left, std::vector<Ref>& right) {
        Aabb cbox;
        for (const Ref& r : refs) cbox.grow(centre(r.box));
        const glm::vec3 e = cbox.hi - cbox.lo;
        const int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
        const auto mid = refs.begin() + static_cast<std::ptrdiff_t>(refs.size() / 2);
        if (e[axis] > 0.0f)
            std::nth_element(refs.begin(), mid, refs.end(),
                             [axis](const Ref& x, const Ref& y) { return centre(x.box)[axis] < centre(y.box)[axis]; });
        left.assign(refs.begin(), mid);
        right.assign(mid, refs.end());
    }

    std::span<const Shape> shapes_;
    SbvhOptions opt_;
    float rootArea_ = 0.0f;
    std::atomic<int>& freeThreads_;
    std::vector<BvhBuildNode>* nodes_ = nullptr;
    std::vector<std::uint32_t>* prims_ = nullptr;
    std::vector<std::future<Subtree>> forks_;
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void splitReference(const Shape& s, const Aabb& box, int axis, float pos, Aabb& left, Aabb& right) {
    left = Aabb{};
    right = Aabb{};
    glm::vec3 v[4];
    int nv = 0;
    if (!s.moves() && s.type == ShapeType::Triangle) {
        v[0] = s.p0;
        v[1] = s.p1;
        v[2] = s.p2;
        nv = 3;
    } else if (!s.moves() && s.type == ShapeType::Quad) {
        v[0] = s.p0;
        v[1] = s.p0 + s.p1;
        v[2] = s.p0 + s.p1 + s.p2;
        v[3] = s.p0 + s.p2;
        nv = 4;
    }
    if (nv == 0) {  // a sphere or a moving shape: its box is cut
        left = box;
        right = box;
        left.hi[axis] = std::min(left.hi[axis], pos);
        right.lo[axis] = std::max(right.lo[axis], pos);
    } else {
        for (int i = 0; i < nv; ++i) {
            const glm::vec3& p = v[i];
            const glm::vec3& q = v[(i + 1) % nv];
            if (p[axis] <= pos) left.grow(p);
            if (p[axis] >= pos) right.grow(p);
            if ((p[axis] < pos && q[axis] > pos) || (p[axis] > pos && q[axis] < pos)) {
                glm::vec3 x = p + (pos - p[axis]) / (q[axis] - p[axis]) * (q - p);
                x[axis] = pos;
                left.grow(x);
                right.grow(x);
            }
        }
        if (!left.empty()) {
            left = widen(left);
            left.hi[axis] = std::min(left.hi[axis], pos);
        }
        if (!right.empty()) {
            right = widen(right);
            right.lo[axis] = std::max(right.lo[axis], pos);
        }
    }
    left = left.empty() ? Aabb{} : intersect(left, box);
    right = right.empty() ? Aabb{} : intersect(right, box);
    if (left.empty()) left = Aabb{};
    if (right.empty()) right = Aabb{};
}

BvhBuildTree buildSbvh(std::span<const Shape> shapes, const SbvhOptions& options) {
    const BvhBuildOptions& b = options.base;
    if (b.binCount < 2 || b.binCount > kMaxBins || b.maxLeafSize < 1 || b.maxDepth < 1 || b.maxDepth > 32 ||
        options.spatialBins < 2 || options.spatialBins > kMaxBins || !(options.maxDuplication >= 0.0f) ||
        !(options.alpha >= 0.0f))
        throw std::invalid_argument(
            "buildSbvh: options out of range (bins in [2,256], leaf >= 1, depth in [1,32], duplication >= 0, alpha >= 0)");
    if (shapes.size() >= std::numeric_limits<std::uint32_t>::max() / 2)
        throw std::invalid_argument("buildSbvh: too many primitives (" + std::to_string(shapes.size()) + ")");
    if (levelsNeeded(shapes.size(), b.maxLeafSize) > b.maxDepth)
        throw std::invalid_argument("buildSbvh: " + std::to_string(shapes.size()) +
                                    " primitives do not fit in leaves of the depth bound");
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const Aabb box = shapeBounds(shapes[i]);
        if (!finite(box.lo) || !finite(box.hi))
            throw std::invalid_argument("buildSbvh: primitive " + std::to_string(i) + " has a non-finite box");
    }
    BvhBuildTree tree;
    const std::size_t n = shapes.size();
    if (n == 0) return tree;
    Task root{0, 0, {}, static_cast<std::size_t>(static_cast<double>(n) * options.maxDuplication)};
    root.refs.resize(n);
    BvhBuildNode rootNode;
    for (std::uint32_t i = 0; i < n; ++i) {
        root.refs[i] = {shapeBounds(shapes[i]), i};
        rootNode.box.grow(root.refs[i].box);
    }
    const unsigned threads = b.threads ? b.threads : std::max(1u, std::thread::hardware_concurrency());
    std::atomic<int> freeThreads(static_cast<int>(std::min(threads, 64u)) - 1);
    Subtree all = SbvhBuilder(shapes, options, rootNode.box.halfArea(), freeThreads).build(std::move(root), rootNode);
    tree.nodes = std::move(all.nodes);
    tree.primIndices = std::move(all.prims);
    tree.maxDepth = all.maxDepth;
    return tree;
}

}  // namespace vkp
