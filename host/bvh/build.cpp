// Binned SAH builder (see build.h). Top-down, with an explicit task stack; each task bins its
// primitives' centroids on the three axes, evaluates the SAH at every bin boundary and partitions
// its range of the index array in place. Subtrees go to other threads while threads are free; the
// result is the same node for node whatever the thread count (a forked subtree is spliced in where
// the sequential build would have put it).
#include "bvh/build.h"
#include "bvh/sbvh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <future>
#include <memory>
#include <thread>
#include <stdexcept>
#include <string>

namespace vkp {

namespace {
/// The box of s where it is (shapeBounds without motion).
Aabb staticBounds(const Shape& s) {
    Aabb b;
    switch (s.type) {
        case ShapeType::Sphere: {
            glm::vec3 r(std::fabs(s.radius));
            b.grow(s.p0 - r);
            b.grow(s.p0 + r);
            break;
        }
        case ShapeType::Quad:
            b.grow(s.p0);
            b.grow(s.p0 + s.p1);
            b.grow(s.p0 + s.p2);
            b.grow(s.p0 + s.p1 + s.p2);
            break;
        case ShapeType::Triangle:
            b.grow(s.p0);
            b.grow(s.p1);
            b.grow(s.p2);
            break;
    }
    return b;
}
}  // namespace

Aabb shapeBounds(const Shape& s) {
    Aabb b = staticBounds(s);
    // A moving shape's positions go monotonically (in float too: rounding is monotone) from time 0
    // to shapeAt(s, 1): the union of both boxes holds it at every time in [0, 1).
    if (s.moves()) b.grow(staticBounds(shapeAt(s, 1.0f)));
    return b;
}

namespace {

constexpr std::uint32_t kMaxBins = 256;
/// Nodes of at most this many primitives evaluate the SAH exactly at every primitive (a sweep over
/// the centroids sorted per axis) instead of binning: better splits, and cheaper than binning.
constexpr std::uint32_t kSweepMax = 16;

struct Bin {
    Aabb box;  // union of the primitives' boxes
    std::uint32_t count = 0;
};

/// A primitive as the builder moves it around: partitions swap these records, so every pass over
/// a node's range reads memory sequentially (rather than through the index array).
struct PrimRef {
    glm::vec3 lo;
    std::uint32_t id;
    glm::vec3 hi;
    glm::vec3 c;  // centroid
};

struct Task {
    std::uint32_t node;
    std::uint32_t begin, end;  // range of refs_ (and of primIndices)
    std::uint32_t depth;
    Aabb cbox;                 // centroid bounds of the range
    int fork = -1;             // >= 0: the subtree of `node` is built by Builder::forks_[fork]; splice it
};

/// A subtree built on its own: nodes[0] is its root, inner nodes' child indices count from 0.
struct Subtree {
    std::vector<BvhBuildNode> nodes;
    std::uint32_t maxDepth = 0;
};

/// Subtrees of at least this many primitives may go to another thread.
constexpr std::uint32_t kForkMin = 4096;

/// Maps a centroid coordinate to a bin: floor((c - lo) * scale) clamped to [0, bins-1].
struct Binner {
    float lo = 0.0f;
    float scale = 0.0f;  // bins / extent; 0 = axis not binned (flat centroid bounds)
    std::uint32_t last = 0;
    std::uint32_t operator()(float c) const {
        float f = (c - lo) * scale;
        return (f > 0.0f) ? static_cast<std::uint32_t>(std::min(f, static_cast<float>(last))) : 0u;
    }
};

struct Split {
    int axis = -1;          // -1: none found
    std::uint32_t bin = 0;  // left = bins [0, bin), right = [bin, binCount)
    float cost = std::numeric_limits<float>::infinity();  // A_L N_L + A_R N_R (not normalised)
    std::uint32_t imbalance = 0;
};

/// Bounds and centroid bounds of `refs`.
void rangeBounds(std::span<const PrimRef> refs, Aabb& box, Aabb& cbox) {
    box = Aabb{};
    cbox = Aabb{};
    for (const PrimRef& r : refs) {
        box.grow(r.lo);
        box.grow(r.hi);
        cbox.grow(r.c);
    }
}

class Builder {
public:
    /// refs: the primitives, shared by the builders of one tree (each works on its own ranges);
    /// freeThreads: threads that may still be started.
    Builder(std::vector<PrimRef>& refs, const BvhBuildOptions& opt, std::atomic<int>& freeThreads)
        : refs_(refs), opt_(opt), freeThreads_(freeThreads) {}

    /// Builds the subtree of `root` (its range of refs, depth and centroid bounds; root.node is
    /// ignored) whose root node, box set, is `rootNode`.
    Subtree build(Task root, const BvhBuildNode& rootNode) {
        Subtree out;
        nodes_ = &out.nodes;
        out.nodes.reserve(2 * ((root.end - root.begin + opt_.maxLeafSize - 1) / opt_.maxLeafSize) + 1);
        out.nodes.push_back(rootNode);
        out.maxDepth = root.depth;
        root.node = 0;
        root.fork = -1;  // the forking builder's marker; here the subtree itself is built
        std::vector<Task> stack;
        stack.push_back(root);
        while (!stack.empty()) {
            Task t = stack.back();
            stack.pop_back();
            if (t.fork >= 0) splice(t, out.maxDepth);
            else process(t, stack, out.maxDepth);
        }
        return out;
    }

private:
    void rangeBounds(std::uint32_t begin, std::uint32_t end, Aabb& box, Aabb& cbox) const {
        vkp::rangeBounds(std::span<const PrimRef>(refs_).subspan(begin, end - begin), box, cbox);
    }

    void makeLeaf(const Task& t, std::uint32_t& maxDepth) {
        BvhBuildNode& node = (*nodes_)[t.node];
        node.index = t.begin;
        node.count = t.end - t.begin;
        maxDepth = std::max(maxDepth, t.depth);
    }

    void process(const Task& t, std::vector<Task>& stack, std::uint32_t& maxDepth) {
        const std::uint32_t n = t.end - t.begin;
        const bool mustSplit = n > opt_.maxLeafSize || (t.depth == 0 && n >= 2);
        if (n == 1) return makeLeaf(t, maxDepth);
        // Depth budget (see build.h): SAH only while a balanced split would still leave a level to
        // spare; the object median halves the range, so levelsNeeded drops by one per level.
        const bool sahAllowed = levelsNeeded(n, opt_.maxLeafSize) < opt_.maxDepth - t.depth;

        Binner binners[3];
        Split best;
        const bool sweep = n <= kSweepMax;
        if (sahAllowed) best = sweep ? findSweepSplit(t) : findSahSplit(t, binners);

        std::uint32_t mid;
        Aabb lbox, rbox, lcbox, rcbox;
        if (best.axis >= 0) {
            const float area = (*nodes_)[t.node].box.halfArea();
            const float ct = opt_.traversalCost, ci = opt_.intersectionCost;
            // Ct + Ci * cost / A < Ci * n, multiplied by A (A may be 0 for collinear points).
            const bool sahWins = ct * area + ci * best.cost < ci * static_cast<float>(n) * area;
            if (!sahWins && !mustSplit) return makeLeaf(t, maxDepth);
            if (sweep) {
                sortRange(t, best.axis);
                mid = t.begin + best.bin;
                rangeBounds(t.begin, mid, lbox, lcbox);
                rangeBounds(mid, t.end, rbox, rcbox);
            } else {
                mid = partition(t, best.axis, binners[best.axis], best.bin, lcbox, rcbox);
                const Bin* b = bins_[best.axis].data();
                for (std::uint32_t k = 0; k < best.bin; ++k) lbox.grow(b[k].box);
                for (std::uint32_t k = best.bin; k < opt_.binCount; ++k) rbox.grow(b[k].box);
            }
        } else {
            if (!mustSplit) return makeLeaf(t, maxDepth);
            mid = medianSplit(t);
            rangeBounds(t.begin, mid, lbox, lcbox);
            rangeBounds(mid, t.end, rbox, rcbox);
        }

        const auto first = static_cast<std::uint32_t>(nodes_->size());
        (*nodes_)[t.node].index = first;
        (*nodes_)[t.node].count = 0;
        BvhBuildNode left, right;
        left.box = lbox;
        right.box = rbox;
        nodes_->push_back(left);
        nodes_->push_back(right);
        Task rightTask{first + 1, mid, t.end, t.depth + 1, rcbox};
        if (t.end - mid >= kForkMin && takeThread(freeThreads_)) {
            // The right subtree on another thread; the marker left in its place splices it in
            // once the left subtree is done, where the sequential build would have put its nodes.
            rightTask.fork = static_cast<int>(forks_.size());
            forks_.push_back(std::async(std::launch::async, [this, rightTask, right] {
                Builder other(refs_, opt_, freeThreads_);
                Subtree sub = other.build(rightTask, right);
                freeThreads_.fetch_add(1);
                return sub;
            }));
        }
        stack.push_back(rightTask);
        stack.push_back({first, t.begin, mid, t.depth + 1, lcbox});
    }

    /// Appends the forked subtree of marker t after the nodes built so far; its root replaces node t.node.
    void splice(const Task& t, std::uint32_t& maxDepth) {
        Subtree sub = forks_[static_cast<std::size_t>(t.fork)].get();
        const auto offset = static_cast<std::uint32_t>(nodes_->size() - 1);  // the subtree's node i (i >= 1) goes to offset + i
        auto moved = [offset](BvhBuildNode n) {
            if (!n.isLeaf()) n.index += offset;  // leaves index the primitives, which do not move
            return n;
        };
        (*nodes_)[t.node] = moved(sub.nodes[0]);
        for (std::size_t i = 1; i < sub.nodes.size(); ++i) nodes_->push_back(moved(sub.nodes[i]));
        maxDepth = std::max(maxDepth, sub.maxDepth);
    }

    /// Bins the task's centroids on each axis with a non-zero extent (into bins_) and returns the
    /// bin boundary of least SAH cost, ties broken towards equal counts.
    Split findSahSplit(const Task& t, Binner (&binners)[3]) {
        const std::uint32_t nb = opt_.binCount;
        bool any = false;
        for (int a = 0; a < 3; ++a) {
            float extent = t.cbox.hi[a] - t.cbox.lo[a];
            float scale = static_cast<float>(nb) / extent;
            binners[a].lo = t.cbox.lo[a];
            binners[a].scale = (extent > 0.0f && std::isfinite(scale)) ? scale : 0.0f;
            binners[a].last = nb - 1;
            any = any || binners[a].scale > 0.0f;
        }
        Split best;
        if (!any) return best;
        for (auto& axisBins : bins_) std::fill_n(axisBins.begin(), nb, Bin{});
        auto& bins = bins_;
        for (std::uint32_t i = t.begin; i < t.end; ++i) {
            const PrimRef& r = refs_[i];
            for (int a = 0; a < 3; ++a) {
                Bin& b = bins[a][binners[a](r.c[a])];
                b.box.lo = glm::min(b.box.lo, r.lo);
                b.box.hi = glm::max(b.box.hi, r.hi);
                ++b.count;
            }
        }
        float rightCost[kMaxBins];
        std::uint32_t rightCount[kMaxBins];
        for (int a = 0; a < 3; ++a) {
            if (binners[a].scale == 0.0f) continue;
            Aabb acc;
            std::uint32_t cnt = 0;
            for (std::uint32_t k = nb - 1; k > 0; --k) {
                acc.grow(bins[a][k].box);
                cnt += bins[a][k].count;
                rightCost[k] = acc.halfArea() * static_cast<float>(cnt);
                rightCount[k] = cnt;
            }
            acc = Aabb{};
            cnt = 0;
            const std::uint32_t n = t.end - t.begin;
            for (std::uint32_t k = 1; k < nb; ++k) {
                acc.grow(bins[a][k - 1].box);
                cnt += bins[a][k - 1].count;
                if (cnt == 0 || rightCount[k] == 0) continue;
                float cost = acc.halfArea() * static_cast<float>(cnt) + rightCost[k];
                std::uint32_t imb = cnt > n / 2 ? cnt - n / 2 : n / 2 - cnt;
                if (cost < best.cost || (cost == best.cost && imb < best.imbalance)) {
                    best = {a, k, cost, imb};
                }
            }
        }
        return best;
    }

    /// Exact SAH for a small node (n <= kSweepMax): per axis with a non-zero centroid extent, the
    /// primitives sorted by centroid (stable insertion sort, the same order sortRange produces)
    /// and every split position evaluated. Split::bin = number of primitives on the left.
    Split findSweepSplit(const Task& t) const {
        const std::uint32_t n = t.end - t.begin;
        Split best;
        std::uint32_t order[kSweepMax];
        float rightCost[kSweepMax];
        for (int a = 0; a < 3; ++a) {
            if (!(t.cbox.hi[a] - t.cbox.lo[a] > 0.0f)) continue;
            for (std::uint32_t i = 0; i < n; ++i) {
                std::uint32_t k = i;
                const float key = refs_[t.begin + i].c[a];
                for (; k > 0 && refs_[t.begin + order[k - 1]].c[a] > key; --k) order[k] = order[k - 1];
                order[k] = i;
            }
            Aabb acc;
            for (std::uint32_t k = n - 1; k > 0; --k) {
                const PrimRef& r = refs_[t.begin + order[k]];
                acc.grow(r.lo);
                acc.grow(r.hi);
                rightCost[k] = acc.halfArea() * static_cast<float>(n - k);
            }
            acc = Aabb{};
            for (std::uint32_t k = 1; k < n; ++k) {
                const PrimRef& r = refs_[t.begin + order[k - 1]];
                acc.grow(r.lo);
                acc.grow(r.hi);
                const float cost = acc.halfArea() * static_cast<float>(k) + rightCost[k];
                const std::uint32_t imb = k > n / 2 ? k - n / 2 : n / 2 - k;
                if (cost < best.cost || (cost == best.cost && imb < best.imbalance)) best = {a, k, cost, imb};
            }
        }
        return best;
    }

    /// Stable insertion sort of a small range of refs_ by centroid on one axis.
    void sortRange(const Task& t, int axis) {
        for (std::uint32_t i = t.begin + 1; i < t.end; ++i) {
            const PrimRef r = refs_[i];
            std::uint32_t k = i;
            for (; k > t.begin && refs_[k - 1].c[axis] > r.c[axis]; --k) refs_[k] = refs_[k - 1];
            refs_[k] = r;
        }
    }

    /// In-place partition of the task's range: bin < splitBin goes left. Returns the first index
    /// of the right part and the children's centroid bounds. Each element is classified once.
    std::uint32_t partition(const Task& t, int axis, const Binner& binner, std::uint32_t splitBin,
                            Aabb& lcbox, Aabb& rcbox) {
        std::uint32_t i = t.begin, j = t.end;
        while (i < j) {
            const glm::vec3 c = refs_[i].c;
            if (binner(c[axis]) < splitBin) {
                lcbox.grow(c);
                ++i;
            } else {
                rcbox.grow(c);
                std::swap(refs_[i], refs_[--j]);
            }
        }
        return i;
    }

    /// Object median on the axis of largest centroid extent (or just the middle index when all
    /// centroids coincide). Both halves are non-empty since n >= 2.
    std::uint32_t medianSplit(const Task& t) {
        const std::uint32_t mid = t.begin + (t.end - t.begin) / 2;
        glm::vec3 e = t.cbox.hi - t.cbox.lo;
        int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
        if (e[axis] > 0.0f) {
            std::nth_element(refs_.begin() + t.begin, refs_.begin() + mid, refs_.begin() + t.end,
                             [axis](const PrimRef& a, const PrimRef& b) { return a.c[axis] < b.c[axis]; });
        }
        return mid;
    }

    std::vector<PrimRef>& refs_;
    BvhBuildOptions opt_;
    std::atomic<int>& freeThreads_;
    std::array<std::array<Bin, kMaxBins>, 3> bins_{};
    std::vector<BvhBuildNode>* nodes_ = nullptr;
    std::vector<std::future<Subtree>> forks_;
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

bool takeThread(std::atomic<int>& freeThreads) {
    int n = freeThreads.load();
    while (n > 0)
        if (freeThreads.compare_exchange_weak(n, n - 1)) return true;
    return false;
}

std::uint32_t levelsNeeded(std::size_t n, std::uint32_t leafSize) {
    const std::size_t leaves = (n + leafSize - 1) / leafSize;
    std::uint32_t k = 0;
    while ((std::size_t(1) << k) < leaves) ++k;
    return k;
}

BvhBuildTree buildBvh(std::span<const Aabb> boxes, std::span<const glm::vec3> centroids,
                      const BvhBuildOptions& options) {
    if (boxes.size() != centroids.size())
        throw std::invalid_argument("buildBvh: boxes and centroids differ in size");
    if (options.binCount < 2 || options.binCount > kMaxBins || options.maxLeafSize < 1 ||
        options.maxDepth < 1 || options.maxDepth > 32)
        throw std::invalid_argument("buildBvh: options out of range (bins in [2,256], leaf >= 1, depth in [1,32])");
    if (boxes.size() >= std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("buildBvh: too many primitives (" + std::to_string(boxes.size()) + ")");
    if (levelsNeeded(boxes.size(), options.maxLeafSize) > options.maxDepth)
        throw std::invalid_argument("buildBvh: " + std::to_string(boxes.size()) +
                                    " primitives do not fit in leaves of the depth bound");
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Aabb& b = boxes[i];
        if (!finite(b.lo) || !finite(b.hi) || !finite(centroids[i]) ||
            !glm::all(glm::lessThanEqual(b.lo, b.hi)))
            throw std::invalid_argument("buildBvh: primitive " + std::to_string(i) +
                                        " has a non-finite or inverted box or centroid");
    }
    BvhBuildTree tree;
    const std::size_t n = boxes.size();
    if (n == 0) return tree;
    std::vector<PrimRef> refs(n);
    for (std::uint32_t i = 0; i < n; ++i) refs[i] = {boxes[i].lo, i, boxes[i].hi, centroids[i]};
    BvhBuildNode root;
    Aabb rootCbox;
    rangeBounds(refs, root.box, rootCbox);
    const unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    std::atomic<int> freeThreads(static_cast<int>(std::min(threads, 64u)) - 1);
    {
        auto builder = std::make_unique<Builder>(refs, options, freeThreads);  // ~21 KiB of bins
        Subtree all = builder->build(Task{0, 0, static_cast<std::uint32_t>(n), 0, rootCbox}, root);
        tree.nodes = std::move(all.nodes);
        tree.maxDepth = all.maxDepth;
    }
    tree.primIndices.resize(n);
    for (std::size_t i = 0; i < n; ++i) tree.primIndices[i] = refs[i].id;
    return tree;
}

BvhBuildTree buildBvh(std::span<const Shape> shapes, const BvhBuildOptions& options) {
    if (options.spatialSplits > 0.0f) {
        SbvhOptions s;
        s.base = options;
        s.maxDuplication = options.spatialSplits;
        return buildSbvh(shapes, s);
    }
    std::vector<Aabb> boxes(shapes.size());
    std::vector<glm::vec3> centroids(shapes.size());
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        boxes[i] = shapeBounds(shapes[i]);
        centroids[i] = 0.5f * (boxes[i].lo + boxes[i].hi);
    }
    return buildBvh(boxes, centroids, options);
}

}  // namespace vkp
