#include "runtime/import/TileTin.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace kiosk::import {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

struct VertexInfo {
    double z = kNan;
    std::int64_t post = -1;  // post index (row * size + column) of a post vertex
    std::uint32_t out = 0;   // index in the stored mesh
};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Kernel>;
using Fb = CGAL::Constrained_triangulation_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact_predicates_tag: crossing lines are allowed (their crossing becomes a vertex).
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;
using Point = Cdt::Point;

// CGAL works in (u, -v): counter-clockwise there is counter-clockwise seen from above (y north).
// Coordinates are snapped to the stored lattice (1/kTinSubdivisions post) before insertion, so
// the triangulation is exact in what is stored.
double snap(double c) {
    const double s = double(io::kTinSubdivisions);
    return std::round(c * s) / s;
}
Point pointAt(double u, double v) {
    return Point(snap(u), -snap(v));
}

class Builder {
public:
    explicit Builder(const TileTinInput& in)
        : mIn(in), mN(in.posts->postsX - 1), mSize(in.posts->postsX) {}

    Result<TileTinResult> run() {
        TileTinResult r;
        insertBorder();
        for (const TinPolyline& line : mIn.lines) r.lineVertices += insertLine(line);
        collectCandidates();
        r.rounds = refine(r.maxError);
        fillCrossings();
        Diagnostics d = emit(r.mesh);
        if (d.hasErrors()) return d;
        return r;
    }

private:
    float post(int i, int j) const {
        return mIn.posts->values[std::size_t(j) * std::size_t(mSize) + std::size_t(i)];
    }
    bool valid(int i, int j) const {
        return i >= 0 && j >= 0 && i < mSize && j < mSize && std::isfinite(post(i, j));
    }

    Cdt::Vertex_handle insertPost(int i, int j, Cdt::Face_handle hint = {}) {
        Cdt::Vertex_handle h = mCdt.insert(Point(double(i), -double(j)), hint);
        h->info().z = double(post(i, j));
        h->info().post = std::int64_t(j) * mSize + i;
        return h;
    }

    void insertBorder() {
        for (int k = 0; k <= mN; ++k)
            for (const auto& [i, j] :
                 {std::pair{k, 0}, std::pair{k, mN}, std::pair{0, k}, std::pair{mN, k}})
                if (valid(i, j)) insertPost(i, j);
    }

    std::size_t insertLine(const TinPolyline& line) {
        Cdt::Vertex_handle prev;
        std::size_t count = 0;
        for (const glm::dvec3& p : line) {
            Cdt::Vertex_handle h = mCdt.insert(pointAt(p.x, p.y));
            if (h->info().post < 0) h->info().z = p.z;
            ++count;
            if (prev != Cdt::Vertex_handle() && prev != h) mCdt.insert_constraint(prev, h);
            prev = h;
        }
        return count;
    }

    void collectCandidates() {
        for (int j = 1; j < mN; ++j)
            for (int i = 1; i < mN; ++i)
                if (valid(i, j) &&
                    !mIn.replaced[std::size_t(j) * std::size_t(mSize) + std::size_t(i)])
                    mCandidates.push_back(std::uint32_t(j * mSize + i));
        mInserted.assign(mCandidates.size(), 0);
    }

    // Height of the surface of face f at (u, -v): the plane through its three vertices.
    static double heightIn(const Cdt::Face_handle& f, const Point& p) {
        const Point a = f->vertex(0)->point(), b = f->vertex(1)->point(), c = f->vertex(2)->point();
        const double za = f->vertex(0)->info().z, zb = f->vertex(1)->info().z,
                     zc = f->vertex(2)->info().z;
        const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
        if (det == 0) return kNan;
        const double wb =
            ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
        const double wc =
            ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
        return za + wb * (zb - za) + wc * (zc - za);
    }

    // Greedy insertion in rounds: per triangle the worst post above tolerance goes in.
    int refine(double& maxError) {
        int rounds = 0;
        struct Worst {
            double error;
            std::size_t candidate;
        };
        std::unordered_map<const void*, Worst> worst;
        for (;;) {
            worst.clear();
            maxError = 0.0;
            Cdt::Face_handle hint;
            for (std::size_t c = 0; c < mCandidates.size(); ++c) {
                if (mInserted[c]) continue;
                const int i = int(mCandidates[c] % std::uint32_t(mSize));
                const int j = int(mCandidates[c] / std::uint32_t(mSize));
                const Point p(double(i), -double(j));
                Cdt::Face_handle f = mCdt.locate(p, hint);
                hint = f;
                double error = std::numeric_limits<double>::infinity();
                if (!mCdt.is_infinite(f)) {
                    const double z = heightIn(f, p);
                    if (std::isfinite(z)) error = std::abs(z - double(post(i, j)));
                }
                if (error <= mIn.tolerance) {
                    maxError = std::max(maxError, error);
                    continue;
                }
                auto [it, fresh] = worst.try_emplace(&*f, Worst{error, c});
                if (!fresh && error > it->second.error) it->second = Worst{error, c};
            }
            if (worst.empty()) return rounds;
            ++rounds;
            Cdt::Face_handle at;
            for (const auto& [face, w] : worst) {
                (void)face;
                mInserted[w.candidate] = 1;
                const int i = int(mCandidates[w.candidate] % std::uint32_t(mSize));
                const int j = int(mCandidates[w.candidate] / std::uint32_t(mSize));
                at = insertPost(i, j, at)->face();
            }
        }
    }

    // Where two lines cross, CGAL adds a vertex without a height: the inverse-distance mean of
    // its neighbours along the constrained edges that have one.
    void fillCrossings() {
        for (auto v = mCdt.finite_vertices_begin(); v != mCdt.finite_vertices_end(); ++v) {
            if (std::isfinite(v->info().z)) continue;
            double sum = 0.0, weight = 0.0;
            auto e = mCdt.incident_edges(v), end = e;
            if (e == nullptr) continue;
            do {
                if (!mCdt.is_infinite(*e) && mCdt.is_constrained(*e)) {
                    const Cdt::Vertex_handle a = e->first->vertex(mCdt.cw(e->second));
                    const Cdt::Vertex_handle b = e->first->vertex(mCdt.ccw(e->second));
                    const Cdt::Vertex_handle o = a == Cdt::Vertex_handle(v) ? b : a;
                    if (std::isfinite(o->info().z)) {
                        const double dist = std::sqrt(
                            CGAL::to_double(CGAL::squared_distance(o->point(), v->point())));
                        const double w = 1.0 / std::max(dist, 1e-9);
                        sum += w * o->info().z;
                        weight += w;
                    }
                }
            } while (++e != end);
            v->info().z = weight > 0 ? sum / weight : kNan;
        }
    }

    bool keep(const Cdt::Face_handle& f) const {
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(f->vertex(k)->info().z)) return false;
        const Point a = f->vertex(0)->point(), b = f->vertex(1)->point(), c = f->vertex(2)->point();
        const double u = (a.x() + b.x() + c.x()) / 3.0, v = -(a.y() + b.y() + c.y()) / 3.0;
        if (mIn.covered && mIn.covered(u, v)) return true;
        // Grid data under the centroid: the post cell's four posts.
        const int i = std::clamp(int(std::floor(u)), 0, mN - 1);
        const int j = std::clamp(int(std::floor(v)), 0, mN - 1);
        return valid(i, j) && valid(i + 1, j) && valid(i, j + 1) && valid(i + 1, j + 1);
    }

    glm::dvec3 postNormal(int i, int j) const {
        // As RtinMesher: central differences, one-sided at borders and next to nodata.
        auto slope = [&](int di, int dj, double spacing) {
            const bool fwd = valid(i + di, j + dj), back = valid(i - di, j - dj);
            const double h = post(i, j);
            if (fwd && back)
                return (double(post(i + di, j + dj)) - post(i - di, j - dj)) / (2 * spacing);
            if (fwd) return (double(post(i + di, j + dj)) - h) / spacing;
            if (back) return (h - double(post(i - di, j - dj))) / spacing;
            return 0.0;
        };
        return glm::normalize(glm::dvec3(-slope(1, 0, mIn.pixelX), slope(0, 1, mIn.pixelY), 1.0));
    }

    Diagnostics emit(io::TinMesh& m) {
        Diagnostics d;
        m.postIntervals = mN;
        m.fullBorder = true;
        for (int k = 0; k <= mN && m.fullBorder; ++k)
            m.fullBorder = valid(k, 0) && valid(k, mN) && valid(0, k) && valid(mN, k);
        std::vector<glm::dvec3> faceNormalSum;
        std::uint32_t count = 0;
        for (auto v = mCdt.finite_vertices_begin(); v != mCdt.finite_vertices_end(); ++v)
            v->info().out = count++;
        m.xy.resize(std::size_t(count) * 2);
        m.z.resize(count);
        m.normals.assign(std::size_t(count) * 3, 0.0f);
        faceNormalSum.assign(count, glm::dvec3(0.0));
        std::vector<std::uint8_t> used(count, 0);
        const double sub = double(io::kTinSubdivisions);
        for (auto v = mCdt.finite_vertices_begin(); v != mCdt.finite_vertices_end(); ++v) {
            const std::uint32_t o = v->info().out;
            m.xy[2 * o] =
                std::uint32_t(std::llround(std::clamp(v->point().x(), 0.0, double(mN)) * sub));
            m.xy[2 * o + 1] =
                std::uint32_t(std::llround(std::clamp(-v->point().y(), 0.0, double(mN)) * sub));
            m.z[o] = float(v->info().z);
        }
        m.indices.clear();
        for (auto f = mCdt.finite_faces_begin(); f != mCdt.finite_faces_end(); ++f) {
            if (!keep(f)) continue;
            std::uint32_t idx[3];
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k) {
                idx[k] = f->vertex(k)->info().out;
                p[k] = glm::dvec3(m.xy[2 * idx[k]] / sub * mIn.pixelX,
                                  -double(m.xy[2 * idx[k] + 1]) / sub * mIn.pixelY, m.z[idx[k]]);
            }
            const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);  // length = 2 * area
            if (!(n.z > 0)) {
                d.error("TERRAIN_TIN", "", "",
                        "a triangle collapses on the stored 1/1024-post lattice (lines cross too "
                        "close together)");
                return d;
            }
            for (int k = 0; k < 3; ++k) {
                m.indices.push_back(idx[k]);
                faceNormalSum[idx[k]] += n;
                used[idx[k]] = 1;
            }
        }
        // Vertices no kept triangle uses (over nodata) are dropped, indices renumbered.
        std::vector<std::uint32_t> remap(count, 0);
        std::uint32_t kept = 0;
        for (auto v = mCdt.finite_vertices_begin(); v != mCdt.finite_vertices_end(); ++v) {
            const std::uint32_t o = v->info().out;
            if (!used[o]) continue;
            glm::dvec3 n;
            if (v->info().post >= 0)
                n = postNormal(int(v->info().post % mSize), int(v->info().post / mSize));
            else
                n = glm::normalize(faceNormalSum[o]);
            m.xy[2 * kept] = m.xy[2 * o];
            m.xy[2 * kept + 1] = m.xy[2 * o + 1];
            m.z[kept] = m.z[o];
            for (int c = 0; c < 3; ++c) m.normals[3 * kept + std::size_t(c)] = float(n[c]);
            remap[o] = kept++;
        }
        m.xy.resize(std::size_t(kept) * 2);
        m.z.resize(kept);
        m.normals.resize(std::size_t(kept) * 3);
        for (std::uint32_t& i : m.indices) i = remap[i];
        if (m.indices.empty()) d.error("TERRAIN_TIN", "", "", "no triangle over data");
        return d;
    }

    const TileTinInput& mIn;
    const int mN, mSize;
    Cdt mCdt;
    std::vector<std::uint32_t> mCandidates;
    std::vector<std::uint8_t> mInserted;
};

}  // namespace

Result<TileTinResult> buildTileTin(const TileTinInput& input) {
    Diagnostics d;
    const io::RasterTile* t = input.posts;
    if (!t || t->postsX != t->postsY || t->postsX < 3 ||
        t->values.size() != std::size_t(t->postsX) * std::size_t(t->postsY) ||
        input.replaced.size() != t->values.size()) {
        d.error("TERRAIN_TIN", "", "", "tile posts and the left-out mask do not match");
        return d;
    }
    return Builder(input).run();
}

void clipPolyline(const TinPolyline& line, double lo, double hi, std::vector<TinPolyline>& out) {
    TinPolyline piece;
    auto flush = [&] {
        if (piece.size() >= 2) out.push_back(piece);
        piece.clear();
    };
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
        // Liang-Barsky against the square [lo, hi]^2.
        const glm::dvec3 a = line[k], b = line[k + 1];
        const glm::dvec3 dir = b - a;
        double t0 = 0.0, t1 = 1.0;
        bool inside = true;
        for (const auto& [p, q] : {std::pair{-dir.x, a.x - lo}, std::pair{dir.x, hi - a.x},
                                   std::pair{-dir.y, a.y - lo}, std::pair{dir.y, hi - a.y}}) {
            if (p == 0) {
                if (q < 0) inside = false;
                continue;
            }
            const double r = q / p;
            if (p < 0)
                t0 = std::max(t0, r);
            else
                t1 = std::min(t1, r);
        }
        if (!inside || t0 > t1) {
            flush();
            continue;
        }
        const glm::dvec3 s = a + t0 * dir, e = a + t1 * dir;
        if (piece.empty() || t0 > 0) {
            flush();
            piece.push_back(s);
        }
        piece.push_back(e);
        if (t1 < 1) flush();
    }
    flush();
}

}  // namespace kiosk::import
