// measure/mass_properties.cpp — polyvol/measure.hpp: volume and mass
// properties from the cone rule's sums (measure/cone.hpp), the other volume
// formulas (measure/methods.hpp), and the guarantees reported with them.
//
// From sums to results. The ten sums are known as intervals: the exact sum
// of the filtered approximations ± a rigorous bound (or a point when exact),
// and every result is a rational function of them (measure/cone_results.hpp,
// a few dozen GMP operations per mesh). For Accuracy::correctly_rounded the
// sums that an undecided result depends on are recomputed exactly (their
// interval becomes a point) and the results re-evaluated: every result is
// the exact value rounded once. For Accuracy::fast the results are the point
// values and the error bounds are the intervals' half-widths (rounded up).
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/fingerprint.hpp"
#include "exact/rational.hpp"
#include "measure/cone.hpp"
#include "measure/cone_results.hpp"
#include "measure/methods.hpp"
#include "polyvol/measure.hpp"

namespace polyvol {
namespace {

using exact::Rational;
using namespace measure::cone;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The cone rule's results with their guarantees.
struct ConeResults {
    std::vector<double> value;
    std::vector<double> bound;  // absolute error bounds (0 when correctly rounded)
    bool correctly_rounded = false;
};

// Volume only, without GMP: round((sum ± bound) / 6) with the superaccumulator.
std::optional<double> volume_decided(const ConeSums& sums) {
    return exact::decided_round_div(sums.sum[kV], sums.bound[kV], 6);
}

ConeResults cone_results(const MeshView& mesh, int count, Accuracy accuracy, double density) {
    if (count == 1 && accuracy == Accuracy::correctly_rounded && density == 1) {
        // The common signed_volume call: no rationals needed, and the range
        // check in the same pass as the filtered sum (filtered_volume: every
        // position for an indexed mesh or below AVX-512, else the
        // coordinates that some face uses, the only ones any sum reads); a
        // coordinate out of the safe range (or not finite) that the check
        // sees sends the call down the general path below, which checks
        // every coordinate and takes the big-integer path (or gives NaN).
        // The cheaper origin form first when it is likely to decide; the
        // translated form when it does not (same result: correctly rounded).
        // Each call reads the kernel level afresh (a test may cap it
        // meanwhile): an unsafe verdict from the second one also sends the
        // call down the general path.
        bool safe = false;
        const VolumeForm form = likely_volume_form(mesh);
        ConeSums sums = filtered_volume(mesh, safe, form);
        std::optional<double> v;
        if (safe) {
            v = volume_decided(sums);
            if (!v && form == VolumeForm::origin) {
                sums = filtered_volume(mesh, safe, VolumeForm::translated);
                if (safe) v = volume_decided(sums);
            }
        }
        if (safe) {
            if (!v) {
                exact_sums(mesh, bit(kV), sums);
                v = volume_decided(sums);
            }
            ConeResults out;
            out.value = {*v, *v};
            out.bound = {0.0, 0.0};
            out.correctly_rounded = true;
            return out;
        }
    }
    const bool finite_density = std::isfinite(density);
    const Rational rho(finite_density ? density : 1.0);
    const int results = result_count(count);
    ConeResults out;
    out.value.assign(static_cast<std::size_t>(results), 0.0);
    out.bound.assign(static_cast<std::size_t>(results), 0.0);

    std::array<Interval, kSumCount> iv;
    auto finish = [&](const std::vector<Result>& res, bool cr) {
        for (int k = 0; k < results; ++k) {
            const auto d = decided(res[k]);
            out.value[k] = d ? *d : kNaN;
        }
        out.correctly_rounded = cr;
    };

    const Range range = coordinate_range(mesh);
    if (range != Range::safe) {
        // Outside the range where expansions are exact: big integers.
        RationalSums rs = gmp_sums(mesh, count);
        if (!rs.ok) {
            out.value.assign(static_cast<std::size_t>(results), kNaN);
            out.bound.assign(static_cast<std::size_t>(results), kNaN);
            return out;
        }
        for (int k = 0; k < count; ++k) iv[k] = point(rs.sum[k]);
        finish(evaluate(iv, count, rho), true);
    } else {
        const bool fast = accuracy == Accuracy::fast;
        ConeSums sums = filtered_sums(mesh, count, fast ? Precision::fast : Precision::double_double);
        auto intervals = [&](bool with_bounds) {
            for (int k = 0; k < count; ++k) iv[k] = interval(sums.sum[k], with_bounds ? sums.bound[k] : 0.0);
        };
        intervals(true);
        std::vector<Result> res = evaluate(iv, count, rho);
        if (fast) {
            intervals(false);
            const std::vector<Result> pt = evaluate(iv, count, rho);
            for (int k = 0; k < results; ++k) {
                const auto d = decided(pt[k]);
                out.value[k] = d ? *d : kNaN;  // a point: always decided (or NaN)
                out.bound[k] = error_bound(res[k], out.value[k]);
            }
        } else {
            if (const uint32_t need = undecided_sums(res); need != 0) {
                exact_sums(mesh, need, sums);
                intervals(true);
                res = evaluate(iv, count, rho);
            }
            finish(res, true);
        }
    }
    if (!finite_density) {
        // density NaN or ±inf: scale in double (no exactness to keep).
        for (int k = 0; k < results; ++k) {
            const bool scaled = k == kMass || (k >= kFirst && k < kCentroid) || k >= kSecond;
            if (scaled) out.value[k] *= density;
        }
    }
    return out;
}

double relative(const ConeResults& r, int first, int n) {
    double err = 0, mag = 0;
    for (int k = first; k < first + n; ++k) {
        err = std::max(err, r.bound[k]);
        mag = std::max(mag, std::fabs(r.value[k]));
    }
    return relative_to(err, mag);
}

double relative_bound(const measure::SumWithBound& s) {
    if (s.error_bound == 0) return 0;
    if (s.value == 0) return kInf;
    return std::nextafter(s.error_bound / std::fabs(s.value), kInf);
}

}  // namespace

std::string_view method_name(Method m) {
    switch (m) {
        case Method::cone: return "cone";
        case Method::prism: return "prism";
        case Method::pyramid: return "pyramid";
        case Method::vtnb: return "vtnb";
    }
    return "?";
}

std::string_view accuracy_name(Accuracy a) {
    switch (a) {
        case Accuracy::correctly_rounded: return "correctly-rounded";
        case Accuracy::fast: return "fast";
    }
    return "?";
}

std::array<double, 6> inertia_from_second_moments(const std::array<double, 6>& m) {
    return {m[1] + m[2], m[0] + m[2], m[0] + m[1], -m[3], -m[4], -m[5]};
}

namespace {
MassProperties measure_with(const MeshView& mesh, const MeasureOptions& options);
}  // namespace

// Accuracy::fast whose bounds say the moments (or the cone volume) may be
// wrong beyond kFastRelativeLimit — cancellation, as for a part far from the
// origin — is computed again correctly rounded, rather than given as
// numbers that mean nothing.
MassProperties mass_properties(const MeshView& mesh, const MeasureOptions& options) {
    if (options.accuracy != Accuracy::fast) return measure_with(mesh, options);
    const MassProperties fast = measure_with(mesh, options);
    const bool volume_ok = options.method != Method::cone ||
                           fast.volume_error_bound <= kFastRelativeLimit * std::abs(fast.volume);
    if (fast.moments_relative_error <= kFastRelativeLimit && volume_ok) return fast;
    MeasureOptions exact = options;
    exact.accuracy = Accuracy::correctly_rounded;
    return measure_with(mesh, exact);
}

namespace {
MassProperties measure_with(const MeshView& mesh, const MeasureOptions& options) {
    MassProperties p;
    p.method = options.method;
    p.accuracy = options.accuracy;
    const int count = options.second_moments ? int{kSumCount} : int{kSxx};
    const ConeResults c = cone_results(mesh, count, options.accuracy, options.density);
    auto copy = [&](auto& dst, int first) {
        for (std::size_t i = 0; i < dst.size(); ++i)
            dst[i] = first < result_count(count) ? c.value[static_cast<std::size_t>(first) + i] : kNaN;
    };
    copy(p.first_moments, kFirst);
    copy(p.centroid, kCentroid);
    copy(p.second_moments, kSecond);
    copy(p.inertia_origin, kInertiaOrigin);
    copy(p.inertia_centroid, kInertiaCentroid);
    p.moments_correctly_rounded = c.correctly_rounded;
    if (c.correctly_rounded) {
        p.moments_relative_error = 0x1p-53;
    } else {
        p.moments_relative_error = std::max(relative(c, kFirst, 3), relative(c, kCentroid, 3));
        if (options.second_moments)
            p.moments_relative_error = std::max({p.moments_relative_error, relative(c, kSecond, 6),
                                                 relative(c, kInertiaOrigin, 6), relative(c, kInertiaCentroid, 6)});
    }

    measure::SumWithBound area{}, length{};
    bool franklin_area = false;  // vtnb on a closed surface: area and length from Franklin's sums
    // Franklin's pyramid sum is the cone rule's sum exactly, for every mesh
    // (pyramid.cpp): correctly rounded, it is the cone's volume and mass.
    const bool cone_volume = options.method == Method::cone ||
                             (options.method == Method::pyramid && options.accuracy == Accuracy::correctly_rounded);
    if (cone_volume) {
        p.volume = c.value[kVolume];
        p.mass = c.value[kMass];
        p.volume_correctly_rounded = c.correctly_rounded;
        p.volume_error_bound = c.bound[kVolume];
    } else if (options.method == Method::prism && options.accuracy == Accuracy::correctly_rounded) {
        p.volume = measure::prism_volume_correctly_rounded(mesh);
        p.volume_correctly_rounded = !std::isnan(p.volume);
        p.volume_error_bound = p.volume_correctly_rounded ? 0.0 : kNaN;
    } else if (options.method == Method::vtnb) {
        const measure::VtnbResult v = measure::vtnb_measures(mesh);
        p.volume = v.volume.value;
        p.volume_error_bound = v.volume.error_bound;
        // Franklin's area and length hold for closed surfaces only; on an
        // open one they are sums about the local origin, not the surface's
        // area and edge length, which the direct sums below then give.
        if (core::fingerprint::mesh_closedness(mesh) == Closedness::closed) {
            area = v.area;
            length = v.length;
            franklin_area = true;
        }
    } else {
        const measure::SumWithBound v =
            options.method == Method::prism ? measure::prism_volume(mesh) : measure::pyramid_volume(mesh);
        p.volume = v.value;
        p.volume_error_bound = v.error_bound;
    }
    // Otherwise the mass is density × volume rounded again (not covered by
    // moments_correctly_rounded).
    if (!cone_volume) p.mass = options.density * p.volume;
    if (!franklin_area) {
        area = measure::fan_area(mesh);
        if (options.edge_length) length = measure::welded_edge_length(mesh);
    }
    p.area = area.value;
    p.area_relative_error = relative_bound(area);
    p.edge_length = options.edge_length ? length.value : kNaN;
    p.edge_length_relative_error = options.edge_length ? relative_bound(length) : kNaN;
    return p;
}
}  // namespace

double signed_volume(const MeshView& mesh, Method method, Accuracy accuracy) {
    switch (method) {
        case Method::cone: return cone_results(mesh, 1, accuracy, 1.0).value[kVolume];
        case Method::prism:
            return accuracy == Accuracy::correctly_rounded ? measure::prism_volume_correctly_rounded(mesh)
                                                           : measure::prism_volume(mesh).value;
        case Method::pyramid:  // the cone's sum exactly (pyramid.cpp)
            return accuracy == Accuracy::correctly_rounded ? cone_results(mesh, 1, accuracy, 1.0).value[kVolume]
                                                           : measure::pyramid_volume(mesh).value;
        case Method::vtnb: return measure::vtnb_measures(mesh).volume.value;
    }
    return kNaN;
}

double surface_area(const MeshView& mesh) { return measure::fan_area(mesh).value; }

double total_edge_length(const MeshView& mesh) { return measure::welded_edge_length(mesh).value; }

}  // namespace polyvol
