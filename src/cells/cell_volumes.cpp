// cells/cell_volumes.cpp — check_cell_mesh and cell_volumes (polyvol/cells.hpp).
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "cells/cell_faces.hpp"
#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "exact/expansion.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/cells.hpp"

namespace polyvol {
namespace cells {

CellFaces cell_faces(const CellMeshView& m) {
    CellFaces cf;
    cf.offsets.assign(m.cell_count() + 1, 0);
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        ++cf.offsets[m.owner[f] + 1];
        if (m.neighbour[f] != kNoCell) ++cf.offsets[m.neighbour[f] + 1];
    }
    for (std::size_t c = 0; c < m.cell_count(); ++c) cf.offsets[c + 1] += cf.offsets[c];
    cf.faces.resize(cf.offsets.back());
    std::vector<uint32_t> next(cf.offsets.begin(), cf.offsets.end() - 1);
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        cf.faces[next[m.owner[f]]++] = static_cast<uint32_t>(f) << 1;
        if (m.neighbour[f] != kNoCell) cf.faces[next[m.neighbour[f]]++] = (static_cast<uint32_t>(f) << 1) | 1u;
    }
    return cf;
}

Mesh boundary_surface(const CellMeshView& m) {
    Mesh out;
    out.positions.assign(m.points.begin(), m.points.end());
    for (std::size_t f = 0; f < m.face_count(); ++f)
        if (m.neighbour[f] == kNoCell)
            face_triangles(m.face(f), m.points, [&](uint32_t a, uint32_t b, uint32_t d) {
                out.indices.insert(out.indices.end(), {a, b, d});
            });
    return out;
}

}  // namespace cells

namespace {

std::string arrays_defect(const CellMeshView& m, uint32_t& face) {
    const std::size_t faces = m.face_count();
    if (m.points.size() % 3 != 0) return "the points array's length is not a multiple of 3";
    if (m.face_offsets.empty() || m.face_offsets[0] != 0) return "the face offsets must start with 0";
    if (m.face_offsets.back() != m.face_points.size()) return "the face offsets must end at the face points' length";
    if (m.owner.size() != faces || m.neighbour.size() != faces)
        return "owner and neighbour need one entry per face (" + std::to_string(faces) + ")";
    if (faces >= (std::size_t{1} << 31)) return "more than 2^31 faces";
    for (std::size_t f = 0; f < faces; ++f) {
        face = static_cast<uint32_t>(f);
        const std::string which = "face " + std::to_string(f);
        if (m.face_offsets[f + 1] < m.face_offsets[f] + 3) return which + " has fewer than 3 points";
        for (const uint32_t p : m.face(f))
            if (p >= m.point_count()) return which + " names point " + std::to_string(p) + ", beyond the points";
        if (m.owner[f] >= m.cell_count()) return which + " has owner cell " + std::to_string(m.owner[f]) + ", beyond the cells";
        if (m.neighbour[f] != kNoCell && m.neighbour[f] >= m.cell_count())
            return which + " has neighbour cell " + std::to_string(m.neighbour[f]) + ", beyond the cells";
        if (m.neighbour[f] == m.owner[f]) return which + " has the same cell on both sides";
    }
    face = kNoCell;
    return "";
}

// Whether cell c's faces close: each polygon edge {p, q} (points compared by
// index) used as often from p to q as from q to p, its neighbour faces
// reversed. `edges` is scratch.
bool cell_closes(const CellMeshView& m, const cells::CellFaces& cf, std::size_t c,
                 std::vector<std::array<uint32_t, 3>>& edges) {
    edges.clear();
    for (const uint32_t entry : cf.of(c)) {
        const std::span<const uint32_t> v = m.face(entry >> 1);
        const bool reversed = (entry & 1u) != 0;
        for (std::size_t i = 0; i < v.size(); ++i) {
            uint32_t p = v[i], q = v[(i + 1) % v.size()];
            if (reversed) std::swap(p, q);
            if (p == q) continue;
            edges.push_back({std::min(p, q), std::max(p, q), p < q ? 1u : 0u});
        }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        long balance = 0;
        for (; j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]; ++j)
            balance += edges[j][2] != 0 ? 1 : -1;
        if (balance != 0) return false;
        i = j;
    }
    return !cf.of(c).empty();
}

bool in_exact_range(const CellMeshView& m) {
    for (const double x : m.points)
        if (!exact::in_safe_range(x)) return false;
    return true;
}

}  // namespace

std::optional<CellMeshDefect> check_cell_mesh(const CellMeshView& m) {
    uint32_t face = kNoCell;
    const std::string arrays = arrays_defect(m, face);
    if (!arrays.empty()) return CellMeshDefect{arrays, kNoCell, face};
    const cells::CellFaces cf = cells::cell_faces(m);
    std::atomic<std::size_t> first{m.cell_count()};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.cell_count(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          std::vector<std::array<uint32_t, 3>> edges;
                          for (std::size_t c = r.begin(); c < r.end() && c < first.load(); ++c)
                              if (!cell_closes(m, cf, c, edges)) {
                                  std::size_t seen = first.load();
                                  while (c < seen && !first.compare_exchange_weak(seen, c)) {
                                  }
                                  break;
                              }
                      });
    const std::size_t c = first.load();
    if (c == m.cell_count()) return std::nullopt;
    const std::string what = cf.of(c).empty() ? " has no faces" : "'s faces do not close (an edge of its faces is used "
                                                                  "more often in one direction than in the other)";
    return CellMeshDefect{"cell " + std::to_string(c) + what, static_cast<uint32_t>(c), kNoCell};
}

CellVolumes cell_volumes(const CellMeshView& m) {
    if (const auto defect = check_cell_mesh(m)) throw std::invalid_argument(defect->message);
    if (!in_exact_range(m))
        throw std::invalid_argument("a point's coordinate is outside 0 and 2^-160 .. 2^190 in magnitude");
    const cells::CellFaces cf = cells::cell_faces(m);
    CellVolumes r;
    r.volumes.resize(m.cell_count());
    tbb::combinable<exact::ExactSum> totals;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.cell_count(), 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          exact::ExactSum& total = totals.local();
                          double det[exact::kDetTerms];
                          for (std::size_t c = range.begin(); c < range.end(); ++c) {
                              // 6 V_c = Σ ± det(a, b, d) over the cell's face triangles, exactly.
                              exact::ExactSum cell;
                              for (const uint32_t entry : cf.of(c)) {
                                  const double sign = (entry & 1u) != 0 ? -1.0 : 1.0;
                                  face_triangles(m.face(entry >> 1), m.points, [&](uint32_t a, uint32_t b, uint32_t d) {
                                      const int n = exact::det3_exact<false>(&m.points[3 * std::size_t{a}],
                                                                             &m.points[3 * std::size_t{b}],
                                                                             &m.points[3 * std::size_t{d}], det);
                                      for (int i = 0; i < n; ++i) cell.add(sign * det[i]);
                                  });
                              }
                              r.volumes[c] = cell.round_div(6);
                              total.merge(cell);
                          }
                      });
    exact::ExactSum total;
    totals.combine_each([&](const exact::ExactSum& s) { total.merge(s); });
    r.total = total.round_div(6);
    r.negative_cells = static_cast<std::size_t>(
        std::count_if(r.volumes.begin(), r.volumes.end(), [](double v) { return v < 0; }));
    for (std::size_t f = 0; f < m.face_count(); ++f) r.face_triangles += m.face(f).size() - 2;
    return r;
}

double covered_volume(const CellMeshView& m) {
    if (const auto defect = check_cell_mesh(m)) throw std::invalid_argument(defect->message);
    const Mesh outside = cells::boundary_surface(m);
    const SolidVolume s = solid_volume(outside.view(), {.moments = false, .within_shells = true});
    return s.status == BooleanStatus::ok ? s.properties.volume : NAN;
}

}  // namespace polyvol
