// The streaming soup accumulator (polyvol/soup.hpp) against the corpus'
// exact figures and the full path (mass_properties), window splits, far
// offsets, exact ties, non-finite input and the closedness fingerprint.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/files.hpp"
#include "common/manifest.hpp"
#include "exact/exact_sum.hpp"
#include "common/kernel_levels.hpp"
#include "measure/soup_testing.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/soup.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace {

namespace fs = std::filesystem;
using namespace polyvol;

const fs::path& kCorpus = test::corpus_dir();

uint64_t bits(double x) { return std::bit_cast<uint64_t>(x); }

// Binary STL records (no header) from float triangles (9 floats each).
std::vector<std::byte> records_of(const std::vector<float>& tri) {
    const std::size_t n = tri.size() / 9;
    std::vector<std::byte> out(50 * n);
    for (std::size_t t = 0; t < n; ++t) std::memcpy(&out[50 * t + 12], &tri[9 * t], 36);
    return out;
}

// The same triangles as a soup Mesh (float32 widened exactly).
Mesh mesh_of(const std::vector<float>& tri) {
    Mesh m;
    for (std::size_t t = 0; t < tri.size() / 9; ++t) {
        const uint32_t a = m.add_vertex(tri[9 * t], tri[9 * t + 1], tri[9 * t + 2]);
        const uint32_t b = m.add_vertex(tri[9 * t + 3], tri[9 * t + 4], tri[9 * t + 5]);
        const uint32_t c = m.add_vertex(tri[9 * t + 6], tri[9 * t + 7], tri[9 * t + 8]);
        m.add_triangle(a, b, c);
    }
    return m;
}

// A closed UV sphere as float triangles (radius r, centre (o, o, o)).
std::vector<float> sphere(int rings, int segments, double r, double o) {
    auto P = [&](int i, double ph) {  // ring i of rings (the poles exactly on the axis)
        const double th = std::numbers::pi * i / rings;
        const double st = i == 0 || i == rings ? 0.0 : std::sin(th);
        const double ct = i == 0 ? 1.0 : (i == rings ? -1.0 : std::cos(th));
        return std::array<float, 3>{static_cast<float>(o + r * st * std::cos(ph)),
                                    static_cast<float>(o + r * st * std::sin(ph)), static_cast<float>(o + r * ct)};
    };
    std::vector<float> out;
    auto tri = [&](const std::array<float, 3>& a, const std::array<float, 3>& b, const std::array<float, 3>& c) {
        out.insert(out.end(), a.begin(), a.end());
        out.insert(out.end(), b.begin(), b.end());
        out.insert(out.end(), c.begin(), c.end());
    };
    const double pi = std::numbers::pi;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double p0 = 2 * pi * j / segments, p1 = 2 * pi * ((j + 1) % segments) / segments;
            if (i > 0) tri(P(i, p0), P(i + 1, p0), P(i, p1));
            if (i + 1 < rings) tri(P(i, p1), P(i + 1, p0), P(i + 1, p1));
        }
    return out;
}

void expect_same(const SoupResult& a, const SoupResult& b) {
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.closed, b.closed);
    EXPECT_EQ(a.passes, b.passes);
    EXPECT_EQ(bits(a.properties.volume), bits(b.properties.volume));
    EXPECT_EQ(bits(a.properties.area), bits(b.properties.area));
    EXPECT_EQ(bits(a.properties.area_relative_error), bits(b.properties.area_relative_error));
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(bits(a.properties.first_moments[k]), bits(b.properties.first_moments[k]));
        EXPECT_EQ(bits(a.properties.centroid[k]), bits(b.properties.centroid[k]));
    }
    EXPECT_EQ(bits(a.properties.mass), bits(b.properties.mass));
    EXPECT_EQ(a.properties.moments_correctly_rounded, b.properties.moments_correctly_rounded);
}

bool same_sum(const exact::ExactSum& a, const exact::ExactSum& b) {
    exact::ExactSum d = a;
    d.subtract(b);
    return d.sign() == 0;
}

// soup_properties with pass 1's exact sums (measure/soup_testing.hpp).
struct Recorded {
    SoupResult result;
    measure::SoupPass1Sums pass1;
};
Recorded recorded(const Float32Triangles& t, uint64_t seed) {
    Recorded r;
    measure::record_soup_pass1(&r.pass1);
    r.result = soup_properties(t, seed);
    measure::record_soup_pass1(nullptr);
    return r;
}

// The same pass-1 sums, exactly (the volume's, not just its rounding).
void expect_same_pass1(const measure::SoupPass1Sums& a, const measure::SoupPass1Sums& b) {
    EXPECT_TRUE(same_sum(a.volume, b.volume)) << "pass-1 volume sum";
    EXPECT_TRUE(same_sum(a.volume_magnitude, b.volume_magnitude)) << "pass-1 volume magnitude";
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(same_sum(a.moments[k], b.moments[k])) << "pass-1 moment " << k;
    EXPECT_TRUE(same_sum(a.moments_magnitude, b.moments_magnitude)) << "pass-1 moments' magnitude";
    EXPECT_TRUE(same_sum(a.area2, b.area2)) << "pass-1 area";
    EXPECT_TRUE(same_sum(a.cross, b.cross)) << "pass-1 cross products";
}

// What pass 1 computes besides the volume changes nothing else: for every
// reduced SoupWants the same pass-1 volume sums (exactly), the same volume
// (in no more passes), the same fingerprint when it is asked for, NaN for what is not;
// and soup_volume gives the same bits.
void expect_wants_agree(const Float32Triangles& t, const Recorded& full, uint64_t seed) {
    for (const SoupWants w : {SoupWants{true, false}, SoupWants{false, true}, SoupWants{false, false}}) {
        SCOPED_TRACE(testing::Message() << "closedness " << w.closedness << ", moments and area " << w.moments_and_area);
        measure::SoupPass1Sums p1;
        measure::record_soup_pass1(&p1);
        const SoupResult r = soup_properties(t, seed, w);
        measure::record_soup_pass1(nullptr);
        EXPECT_EQ(r.computed.closedness, w.closedness);
        EXPECT_EQ(r.computed.moments_and_area, w.moments_and_area);
        EXPECT_EQ(r.triangles, full.result.triangles);
        EXPECT_EQ(r.nonfinite, full.result.nonfinite);
        // The passes depend on what is asked (the moments may need the exact
        // pass, which then also decides the volume without pass 2).
        if (w.moments_and_area) {
            EXPECT_EQ(r.passes, full.result.passes);
        }
        EXPECT_EQ(bits(r.properties.volume), bits(full.result.properties.volume));
        if (!full.result.nonfinite) {
            EXPECT_TRUE(same_sum(p1.volume, full.pass1.volume)) << "pass-1 volume sum";
            EXPECT_TRUE(same_sum(p1.volume_magnitude, full.pass1.volume_magnitude)) << "pass-1 volume magnitude";
        }
        if (w.closedness) {
            EXPECT_EQ(r.closed, full.result.closed);
            EXPECT_EQ(r.fingerprint, full.result.fingerprint);
        } else {
            EXPECT_FALSE(r.closed);
            EXPECT_EQ(r.fingerprint, (std::array<uint64_t, 4>{}));  // soup.hpp: 0 when not computed
        }
        if (w.moments_and_area) {
            EXPECT_EQ(bits(r.properties.area), bits(full.result.properties.area));
            for (int k = 0; k < 3; ++k) EXPECT_EQ(bits(r.properties.centroid[k]), bits(full.result.properties.centroid[k]));
        } else {
            EXPECT_TRUE(std::isnan(r.properties.area));
            EXPECT_TRUE(std::isnan(r.properties.area_relative_error));
            for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isnan(r.properties.centroid[k]) && std::isnan(r.properties.first_moments[k]));
        }
    }
    EXPECT_EQ(bits(soup_volume(t)), bits(full.result.properties.volume));
}

// Feeds rec in windows of `window` triangles (a multiple of 32), in a shuffled order.
SoupResult windowed(const std::vector<std::byte>& rec, std::size_t window, uint64_t seed) {
    SoupAccumulator acc(seed);
    const std::size_t n = rec.size() / 50;
    std::vector<std::size_t> starts;
    for (std::size_t s = 0; s < n; s += window) starts.push_back(s);
    std::mt19937 rng(static_cast<unsigned>(window));
    std::shuffle(starts.begin(), starts.end(), rng);
    do {
        for (std::size_t s : starts) {
            const std::size_t k = std::min(window, n - s);
            acc.add(stl_records(std::span<const std::byte>(rec).subspan(50 * s, 50 * k)), s);
        }
    } while (acc.next_pass());
    return acc.result();
}

struct CorpusStl {
    std::string path;
    bool closed = false;
    double volume = 0;
    double area = 0;
    std::array<double, 3> centroid{};
    bool has_centroid = false;
};

std::vector<CorpusStl> corpus_binary_stls() {
    std::vector<CorpusStl> out;
    for (const auto& e : test::corpus_manifest()) {
        if (e.value("format", "") != "stl" || e.value("encoding", "") != "binary_le") continue;
        CorpusStl c;
        c.path = e["path"].get<std::string>();
        c.closed = e["topology"]["closed_2_cycle"].get<bool>();
        c.volume = test::corpus_reference(e["volume"]);
        c.area = std::strtod(e["surface_area"]["decimal30"].get<std::string>().c_str(), nullptr);
        if (e["centroid"].is_object()) {
            c.has_centroid = true;
            const char* axes[3] = {"x", "y", "z"};
            for (int k = 0; k < 3; ++k) c.centroid[k] = test::corpus_reference(e["centroid"][axes[k]]);
        }
        out.push_back(c);
    }
    return out;
}

TEST(Soup, EveryCorpusBinaryStlMatchesTheManifestAndTheFullPath) {
    const auto files = corpus_binary_stls();
    ASSERT_GE(files.size(), 15u) << "corpus missing at " << kCorpus;
    int closed = 0;
    for (const CorpusStl& c : files) {
        SCOPED_TRACE(c.path);
        const auto bytes = polyvol::test::read_bytes(kCorpus / c.path);
        ASSERT_GE(bytes.size(), 84u);
        const auto rec = std::span<const std::byte>(bytes).subspan(84);
        const SoupResult s = soup_properties(stl_records(rec), 7);
        // The fingerprint is zero exactly for the closed 2-cycles.
        EXPECT_EQ(s.closed, c.closed);
        EXPECT_FALSE(s.nonfinite);
        // The volume (about the origin, also for open surfaces) is the exact value rounded once.
        EXPECT_TRUE(s.properties.volume_correctly_rounded);
        EXPECT_EQ(bits(s.properties.volume), bits(c.volume)) << s.properties.volume << " vs " << c.volume;
        const LoadedMesh full = read_mesh_file((kCorpus / c.path).string());
        const MassProperties mp = mass_properties(full.mesh.view());
        EXPECT_EQ(bits(s.properties.volume), bits(mp.volume));
        EXPECT_EQ(s.triangles, full.mesh.face_count());
        // The area within its stated bound of the exact figure; the first
        // moments and the centroid correctly rounded, as the loaded mesh's.
        EXPECT_LE(std::fabs(s.properties.area - c.area), s.properties.area_relative_error * c.area);
        EXPECT_LT(s.properties.area_relative_error, 1e-13);
        EXPECT_TRUE(s.properties.moments_correctly_rounded);
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(bits(s.properties.first_moments[k]), bits(mp.first_moments[k])) << "axis " << k;
            EXPECT_EQ(bits(s.properties.centroid[k]), bits(mp.centroid[k])) << "axis " << k;
            if (c.has_centroid && c.volume != 0) {
                EXPECT_LE(std::fabs(s.properties.centroid[k] - c.centroid[k]),
                          std::fabs(c.centroid[k]) * 0x1p-52 + 1e-300) << "axis " << k;
            }
        }
        if (c.closed) ++closed;
        // Another key gives the same verdict.
        EXPECT_EQ(soup_properties(stl_records(rec), 12345).closed, c.closed);
    }
    EXPECT_GE(closed, 10);
}

TEST(Soup, EveryKernelLevelGivesTheSameBits) {
    // 0 portable, 1 AVX2 + FMA + AES-NI, 2 AVX-512 + VAES (capped to what the CPU has).
    auto files = corpus_binary_stls();
    std::vector<std::vector<std::byte>> inputs;
    for (const CorpusStl& c : files) {
        const auto bytes = polyvol::test::read_bytes(kCorpus / c.path);
        inputs.emplace_back(bytes.begin() + 84, bytes.end());
    }
    inputs.push_back(records_of(sphere(40, 70, 2, 0.5)));  // also a block count that is not a multiple of 4
    inputs.push_back(records_of(sphere(7, 5, 1, 0)));
    for (const auto& rec : inputs) {
        polyvol::test::cap_kernel_level(-1);
        const Recorded best = recorded(stl_records(rec), 3);
        for (int level : polyvol::test::kLevels) {
            SCOPED_TRACE(level);
            polyvol::test::cap_kernel_level(level);
            const Recorded s = recorded(stl_records(rec), 3);
            expect_same(best.result, s.result);
            expect_same_pass1(best.pass1, s.pass1);
            expect_wants_agree(stl_records(rec), s, 3);
            // Every kernel hashes alike (AES rounds), so the fingerprints agree too.
            EXPECT_EQ(s.result.fingerprint, best.result.fingerprint);
        }
    }
    polyvol::test::cap_kernel_level(-1);
}

// Random triangles with repeated coordinates, ±0.0, subnormals and large
// magnitudes, written with the given stride and offset.
std::vector<std::byte> random_records(std::size_t n, std::size_t stride, std::size_t offset, unsigned seed) {
    std::mt19937 rng(seed);
    const float pool[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 3.25f, -7.75f, 1e-40f, -1e-40f, 1e30f, -2.5e-3f};
    std::uniform_int_distribution<int> pick(0, 2 * static_cast<int>(std::size(pool)) - 1);
    std::uniform_real_distribution<float> any(-100.0f, 100.0f);
    std::vector<std::byte> out(stride * n);
    for (std::size_t t = 0; t < n; ++t)
        for (int k = 0; k < 9; ++k) {
            const int i = pick(rng);
            const float f = i < static_cast<int>(std::size(pool)) ? pool[i] : any(rng);
            std::memcpy(&out[stride * t + offset + 4 * k], &f, 4);
        }
    return out;
}

TEST(Soup, EveryKernelLevelGivesTheSameBitsForEveryBlockTail) {
    // 1 .. 70 triangles: every fill of the last block of 32 (and of its groups
    // of 4 and 8), packed (stride 36) and in STL records; the fingerprints too.
    for (const auto& [stride, offset] : {std::pair<std::size_t, std::size_t>{50, 12}, {36, 0}, {44, 8}}) {
        for (std::size_t n = 1; n <= 70; ++n) {
            SCOPED_TRACE(testing::Message() << "stride " << stride << ", " << n << " triangles");
            const auto rec = random_records(n, stride, offset, static_cast<unsigned>(n));
            const Float32Triangles t{rec.data(), n, stride, offset};
            polyvol::test::cap_kernel_level(-1);
            const Recorded best = recorded(t, 17);
            for (int level : polyvol::test::kLevels) {
                SCOPED_TRACE(level);
                polyvol::test::cap_kernel_level(level);
                const Recorded s = recorded(t, 17);
                expect_same(best.result, s.result);
                expect_wants_agree(t, s, 17);
                expect_same_pass1(best.pass1, s.pass1);
                EXPECT_EQ(s.result.fingerprint, best.result.fingerprint);
            }
        }
    }
    polyvol::test::cap_kernel_level(-1);
}

TEST(Soup, EveryKernelLevelFlagsEveryNonFiniteCoordinate) {
    const auto closed = sphere(10, 16, 1, 0);  // 288 triangles: 9 whole blocks
    const float bad[] = {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN(),
                         std::numeric_limits<float>::signaling_NaN(), std::numeric_limits<float>::infinity(),
                         -std::numeric_limits<float>::infinity()};
    // Also with a partial last block (pass1_avx512_body<false>): of 1
    // triangle, and of 12 (a whole group of 8 and part of the next).
    struct Case {
        std::size_t tail;
        std::vector<std::size_t> where;  // the triangles given a bad coordinate
    };
    const Case cases[] = {{0, {0, 5, 8, 31, 37, 287}}, {1, {287, 288}}, {12, {5, 288, 295, 296, 299}}};
    for (const Case& c : cases) {
        auto tri = closed;
        tri.insert(tri.end(), closed.begin(), closed.begin() + static_cast<long>(9 * c.tail));
        for (int level : polyvol::test::kLevels) {
            polyvol::test::cap_kernel_level(level);
            for (std::size_t t : c.where) {
                for (int k = 0; k < 9; ++k) {
                    for (float b : bad) {
                        SCOPED_TRACE(testing::Message() << "level " << level << ", " << tri.size() / 9
                                                        << " triangles, triangle " << t << ", coordinate " << k);
                        auto rec = records_of(tri);
                        std::memcpy(&rec[50 * t + 12 + 4 * k], &b, 4);
                        const SoupResult s = soup_properties(stl_records(rec), 2);
                        EXPECT_TRUE(s.nonfinite);
                        EXPECT_FALSE(s.closed);
                        EXPECT_TRUE(std::isnan(s.properties.volume));
                        // Without the area (whose sums detect a NaN in the
                        // AVX-512 kernel), the volume's sums must.
                        const SoupResult v = soup_properties(stl_records(rec), 2, SoupWants{true, false});
                        EXPECT_TRUE(v.nonfinite);
                        EXPECT_FALSE(v.closed);
                        EXPECT_TRUE(std::isnan(soup_volume(stl_records(rec))));
                    }
                }
            }
        }
    }
    polyvol::test::cap_kernel_level(-1);
}

#if defined(__linux__)
TEST(Soup, NoKernelReadsPastTheCoordinates) {
    // The last triangle's 36 bytes of coordinates end at an inaccessible page.
    const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    void* map = mmap(nullptr, 3 * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(map, MAP_FAILED);
    auto* bytes = static_cast<std::byte*>(map);
    ASSERT_EQ(mprotect(bytes + 2 * page, page, PROT_NONE), 0);
    for (const auto& [stride, offset] : {std::pair<std::size_t, std::size_t>{50, 12}, {36, 0}}) {
        for (std::size_t n : {1u, 31u, 32u, 45u}) {
            const auto rec = random_records(n, stride, offset, 5);
            // Triangle n - 1's coordinates occupy [offset + (n - 1) stride, + 36).
            std::byte* data = bytes + 2 * page - (offset + (n - 1) * stride + 36);
            std::memcpy(data, rec.data(), (n - 1) * stride + offset + 36);
            const Float32Triangles t{data, n, stride, offset};
            for (int level : polyvol::test::kLevels) {
                SCOPED_TRACE(testing::Message() << "stride " << stride << ", " << n << " triangles, level " << level);
                polyvol::test::cap_kernel_level(level);
                EXPECT_EQ(soup_properties(t, 3).triangles, n);
                EXPECT_EQ(soup_properties(t, 3, SoupWants{false, false}).triangles, n);
            }
        }
    }
    polyvol::test::cap_kernel_level(-1);
    munmap(map, 3 * page);
}
#endif

TEST(Soup, WindowSizesAndOrderGiveIdenticalBits) {
    const auto tri = sphere(120, 200, 3.5, 17.25);  // 47600 triangles
    const auto rec = records_of(tri);
    const SoupResult whole = soup_properties(stl_records(rec), 99);
    EXPECT_TRUE(whole.closed);
    for (std::size_t w : {32u, 96u, 4096u, 8192u, 40000u}) {
        SCOPED_TRACE(w);
        const SoupResult s = windowed(rec, w, 99);
        expect_same(whole, s);
        EXPECT_EQ(s.fingerprint, whole.fingerprint);
    }
    EXPECT_EQ(bits(whole.properties.volume), bits(mass_properties(mesh_of(tri).view()).volume));
}

TEST(Soup, FarFromTheOriginIsStillExact) {
    // Radius 100 at 1e6: float32 steps of 1/16, terms ~1e18 cancelling to ~4e6.
    const auto tri = sphere(60, 90, 100, 1e6);
    const auto rec = records_of(tri);
    const SoupResult s = soup_properties(stl_records(rec), 5);
    EXPECT_TRUE(s.closed);
    EXPECT_TRUE(s.properties.volume_correctly_rounded);
    EXPECT_EQ(s.passes, 2);  // pass 1 cannot decide it, the translated pass 2 can (the moments too)
    const MassProperties mp = mass_properties(mesh_of(tri).view());
    EXPECT_EQ(bits(s.properties.volume), bits(mp.volume));
    EXPECT_EQ(bits(soup_volume(packed_triangles(tri))), bits(mp.volume));
    EXPECT_GT(s.properties.volume, 3e6);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(bits(s.properties.first_moments[k]), bits(mp.first_moments[k]));
        EXPECT_EQ(bits(s.properties.centroid[k]), bits(mp.centroid[k]));
    }
    EXPECT_LE(std::fabs(s.properties.area - mp.area), s.properties.area_relative_error * mp.area + mp.area_relative_error * mp.area);
}

TEST(Soup, AnExactZeroNeedsTheExactPass) {
    // A tetrahedron and its inside-out copy: closed, volume exactly 0.
    const std::vector<float> t = {0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                  0, 0, 0, 0, 0, 1, 0, 1, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::vector<float> both = t;
    for (std::size_t f = 0; f < t.size(); f += 9) {  // reversed copy
        both.insert(both.end(), t.begin() + static_cast<long>(f), t.begin() + static_cast<long>(f) + 3);
        both.insert(both.end(), t.begin() + static_cast<long>(f) + 6, t.begin() + static_cast<long>(f) + 9);
        both.insert(both.end(), t.begin() + static_cast<long>(f) + 3, t.begin() + static_cast<long>(f) + 6);
    }
    const auto rec = records_of(both);
    const SoupResult s = soup_properties(stl_records(rec), 1);
    EXPECT_TRUE(s.closed);
    EXPECT_EQ(s.passes, 2);  // the moments too: straight to the exact pass
    EXPECT_EQ(bits(s.properties.volume), bits(0.0));
    EXPECT_EQ(bits(soup_volume(packed_triangles(both))), bits(0.0));
    EXPECT_EQ(soup_properties(packed_triangles(both), 1, SoupWants{false, false}).passes, 3);
    EXPECT_TRUE(std::isnan(s.properties.centroid[0]));
    // The single tetrahedron: 1/6 in one pass.
    const auto one = records_of(t);
    const SoupResult u = soup_properties(stl_records(one), 1);
    EXPECT_TRUE(u.closed);
    EXPECT_EQ(u.passes, 1);
    EXPECT_EQ(u.properties.volume, 1.0 / 6);
    EXPECT_LE(std::fabs(u.properties.area - (1.5 + std::sqrt(3.0) / 2)), 4 * u.properties.area_relative_error * u.properties.area + 1e-15);
    EXPECT_EQ(u.properties.centroid[0], 0.25);
    EXPECT_EQ(u.properties.first_moments[1], 1.0 / 24);
}

// A cube centred at the origin: every first moment exactly 0, which no
// filter decides, so pass 3 sums them exactly; the centroid is then exactly
// (0, 0, 0), as for the loaded mesh. A density scales the mass and the
// moments, each still rounded once, as mass_properties does.
TEST(Soup, CentredPartsGetExactZeroMomentsAndTheDensityScalesOnce) {
    std::vector<float> tri;
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads)
        for (const auto& t : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}})
            for (int c : t)
                for (int k = 0; k < 3; ++k) tri.push_back((c >> k & 1) ? 0.5f : -0.5f);
    const SoupResult s = soup_properties(packed_triangles(tri), 3);
    EXPECT_TRUE(s.closed);
    EXPECT_EQ(s.passes, 2);
    EXPECT_EQ(s.properties.volume, 1.0);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(bits(s.properties.first_moments[k]), bits(0.0));
        EXPECT_EQ(bits(s.properties.centroid[k]), bits(0.0));
    }
    // An off-centre sphere with a density that is not a power of two.
    const auto sph = sphere(20, 30, 3, 7);
    MeasureOptions o;
    o.density = 7.85;
    o.second_moments = false;
    const MassProperties mp = mass_properties(mesh_of(sph).view(), o);
    const SoupResult d = soup_properties(packed_triangles(sph), 3, SoupWants{.density = 7.85});
    EXPECT_EQ(bits(d.properties.volume), bits(mp.volume));
    EXPECT_EQ(bits(d.properties.mass), bits(mp.mass));
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(bits(d.properties.first_moments[k]), bits(mp.first_moments[k]));
        EXPECT_EQ(bits(d.properties.centroid[k]), bits(mp.centroid[k]));
    }
    EXPECT_NE(d.properties.mass, d.properties.volume);
    const SoupResult v = soup_properties(packed_triangles(sph), 3, SoupWants{.moments_and_area = false, .density = 7.85});
    EXPECT_EQ(bits(v.properties.mass), bits(mp.mass));
    EXPECT_THROW(SoupAccumulator(SoupWants{.density = std::numeric_limits<double>::infinity()}), std::invalid_argument);
    // Bounded moments: pass 1's values within its bound, no exact pass for them.
    const SoupResult f = soup_properties(packed_triangles(sph), 3, SoupWants{.moments = Accuracy::fast, .density = 7.85});
    EXPECT_EQ(f.passes, 1);
    EXPECT_FALSE(f.properties.moments_correctly_rounded);
    EXPECT_GT(f.properties.moments_relative_error, 0.0);
    EXPECT_LT(f.properties.moments_relative_error, 1e-12);  // pass 1's plain sums
    EXPECT_EQ(bits(f.properties.mass), bits(mp.mass));
    // Within the bound of the exact values, so within it plus half an ulp of the correctly rounded ones.
    double largest_first = 0, largest_centroid = 0;
    for (int k = 0; k < 3; ++k) {
        largest_first = std::max(largest_first, std::fabs(f.properties.first_moments[k]));
        largest_centroid = std::max(largest_centroid, std::fabs(f.properties.centroid[k]));
    }
    for (int k = 0; k < 3; ++k) {
        EXPECT_LE(std::fabs(f.properties.first_moments[k] - mp.first_moments[k]),
                  f.properties.moments_relative_error * largest_first + std::fabs(mp.first_moments[k]) * 0x1p-53);
        EXPECT_LE(std::fabs(f.properties.centroid[k] - mp.centroid[k]),
                  f.properties.moments_relative_error * largest_centroid + std::fabs(mp.centroid[k]) * 0x1p-53);
    }
    // The cube's bounded moments: every approximation exactly 0 with a
    // nonzero bound, which no relative bound carries: summed exactly.
    const SoupResult cube = soup_properties(packed_triangles(tri), 3, SoupWants{.moments = Accuracy::fast});
    EXPECT_EQ(cube.passes, 2);
    EXPECT_EQ(cube.properties.moments_relative_error, 0.0);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(bits(cube.properties.centroid[k]), bits(0.0));
    // A negative density (the library takes any finite one) keeps the bound rigorous.
    const SoupResult neg = soup_properties(packed_triangles(sph), 3, SoupWants{.moments = Accuracy::fast, .density = -7.85});
    MeasureOptions on = o;
    on.density = -7.85;
    const MassProperties mn = mass_properties(mesh_of(sph).view(), on);
    EXPECT_GT(neg.properties.moments_relative_error, 0.0);
    for (int k = 0; k < 3; ++k)
        EXPECT_LE(std::fabs(neg.properties.first_moments[k] - mn.first_moments[k]),
                  neg.properties.moments_relative_error * largest_first + std::fabs(mn.first_moments[k]) * 0x1p-53);
}

TEST(Soup, FingerprintSeesEveryKindOfUnbalancedEdge) {
    const auto closed = sphere(10, 16, 1, 0);
    ASSERT_TRUE(soup_properties(stl_records(records_of(closed)), 11).closed);
    // One triangle flipped (two edges used twice the same way), removed (a
    // hole), or duplicated (three edges unbalanced by 1), a duplicated flipped pair
    // (balanced: still closed), and -0.0 for +0.0 (the same point).
    auto flip = closed;
    std::swap_ranges(flip.begin() + 3, flip.begin() + 6, flip.begin() + 6);
    auto hole = closed;
    hole.erase(hole.begin(), hole.begin() + 9);
    auto dup = closed;
    dup.insert(dup.end(), closed.begin(), closed.begin() + 9);
    auto pair = closed;
    pair.insert(pair.end(), closed.begin(), closed.begin() + 9);
    pair.insert(pair.end(), flip.begin(), flip.begin() + 9);
    auto twice = closed;  // every triangle twice: balanced
    twice.insert(twice.end(), closed.begin(), closed.end());
    for (uint64_t seed : {1u, 2u, 3u}) {
        EXPECT_FALSE(soup_properties(stl_records(records_of(flip)), seed).closed);
        EXPECT_FALSE(soup_properties(stl_records(records_of(hole)), seed).closed);
        EXPECT_FALSE(soup_properties(stl_records(records_of(dup)), seed).closed);
        EXPECT_TRUE(soup_properties(stl_records(records_of(pair)), seed).closed);
        EXPECT_TRUE(soup_properties(stl_records(records_of(twice)), seed).closed);
    }
    // The poles of the sphere lie on the z axis: x = y = 0; writing -0.0 in
    // one copy of a vertex must not open the surface.
    auto signed_zero = closed;
    int changed = 0;
    for (float& x : signed_zero)
        if (x == 0 && changed < 5) {
            x = -0.0f;
            ++changed;
        }
    ASSERT_GT(changed, 0);
    EXPECT_TRUE(soup_properties(stl_records(records_of(signed_zero)), 4).closed);
    // And the random key (std::random_device) agrees.
    EXPECT_TRUE(soup_properties(stl_records(records_of(closed))).closed);
    EXPECT_FALSE(soup_properties(stl_records(records_of(flip))).closed);
}

TEST(Soup, NonFiniteCoordinatesAreFlagged) {
    auto tri = sphere(6, 8, 1, 0);
    tri[40] = std::numeric_limits<float>::quiet_NaN();
    SoupResult s = soup_properties(stl_records(records_of(tri)), 1);
    EXPECT_TRUE(s.nonfinite);
    EXPECT_FALSE(s.closed);
    EXPECT_TRUE(std::isnan(s.properties.volume));
    tri[40] = std::numeric_limits<float>::infinity();
    s = soup_properties(stl_records(records_of(tri)), 1);
    EXPECT_TRUE(s.nonfinite);
    EXPECT_TRUE(std::isnan(s.properties.volume));
}

// Random soups near the origin and far from it, of every scale, some
// symmetric (first moments exactly 0), some with degenerate triangles, some
// with a density: the streamed volume, mass, first moments and centroid are
// the loaded mesh's bit for bit, whichever passes they took, and the bounded
// moments lie within their bound of them.
TEST(Soup, RandomSoupsGetTheLoadedMeshsBits) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> unit(-1, 1);
    int passes[4] = {};
    for (int c = 0; c < 600; ++c) {
        SCOPED_TRACE(c);
        const int n = 1 + static_cast<int>(rng() % (c % 50 == 0 ? 20000 : 500));
        const double scale = std::ldexp(1.0, static_cast<int>(rng() % 60) - 30);
        const double offset =
            rng() % 3 == 0 ? 0.0 : std::ldexp(1.0, static_cast<int>(rng() % 40) - 10) * ((rng() & 1) ? 1 : -1);
        const bool symmetric = rng() % 4 == 0;
        std::vector<float> tri;
        for (int t = 0; t < n; ++t) {
            float v[9];
            for (float& x : v) x = static_cast<float>(offset + scale * unit(rng));
            if (rng() % 5 == 0)
                for (int k = 0; k < 3; ++k) v[3 + k] = v[k];
            tri.insert(tri.end(), v, v + 9);
            if (symmetric)
                for (float x : v) tri.push_back(-x);
        }
        MeasureOptions o;
        o.second_moments = false;
        o.edge_length = false;
        o.density = rng() % 3 == 0 ? 7.85 : 1.0;
        const MassProperties mp = mass_properties(mesh_of(tri).view(), o);
        const SoupResult s = soup_properties(packed_triangles(tri), static_cast<uint64_t>(c), SoupWants{.density = o.density});
        const SoupResult f = soup_properties(packed_triangles(tri), static_cast<uint64_t>(c),
                                             SoupWants{.moments = Accuracy::fast, .density = o.density});
        ++passes[s.passes];
        EXPECT_EQ(bits(s.properties.volume), bits(mp.volume));
        EXPECT_EQ(bits(s.properties.mass), bits(mp.mass));
        EXPECT_EQ(bits(f.properties.volume), bits(mp.volume));
        double largest = 0;
        for (int k = 0; k < 3; ++k) largest = std::max(largest, std::fabs(f.properties.first_moments[k]));
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(bits(s.properties.first_moments[k]), bits(mp.first_moments[k])) << k;
            EXPECT_EQ(bits(s.properties.centroid[k]), bits(mp.centroid[k])) << k;
            if (std::isfinite(f.properties.moments_relative_error)) {
                EXPECT_LE(std::fabs(f.properties.first_moments[k] - mp.first_moments[k]),
                          f.properties.moments_relative_error * largest + std::fabs(mp.first_moments[k]) * 0x1p-53);
            }
        }
    }
    // Every route was taken: one read, the translated pass 2, the exact pass.
    EXPECT_GT(passes[1], 0);
    EXPECT_GT(passes[2], 0);
    EXPECT_GT(passes[3], 0);
}

TEST(Soup, ContractErrors) {
    // (Off the origin: a centred sphere's first moments are exactly 0, which takes the exact pass.)
    const auto rec = records_of(sphere(6, 8, 1, 2));
    SoupAccumulator acc(1);
    EXPECT_THROW(acc.add(stl_records(rec), 5), std::invalid_argument);
    EXPECT_THROW(acc.add(Float32Triangles{rec.data(), 3, 20, 0}, 0), std::invalid_argument);
    EXPECT_THROW((void)acc.result(), std::logic_error);
    acc.add(stl_records(rec), 0);
    EXPECT_FALSE(acc.next_pass());
    EXPECT_EQ(acc.result().triangles, rec.size() / 50);
    // No triangles: volume 0, closed.
    const SoupResult empty = soup_properties(Float32Triangles{}, 1);
    EXPECT_EQ(empty.triangles, 0u);
    EXPECT_TRUE(empty.closed);
    EXPECT_EQ(empty.properties.volume, 0.0);
    EXPECT_EQ(soup_volume(Float32Triangles{}), 0.0);
}

TEST(Soup, PackedTrianglesCountWholeTriangles) {
    const auto tri = sphere(6, 8, 1, 0);
    EXPECT_EQ(packed_triangles(tri).count, tri.size() / 9);
    EXPECT_EQ(packed_triangles(std::span<const float>(tri).first(9 * 5 + 8)).count, 5u);
    EXPECT_EQ(packed_triangles(std::span<const float>(tri).first(9 * 5 + 8)).stride, 36u);
    // The packed triangles and their STL records: the same volume.
    EXPECT_EQ(bits(soup_volume(packed_triangles(tri))), bits(soup_properties(stl_records(records_of(tri)), 1).properties.volume));
}

TEST(Soup, EveryCorpusBinaryStlReadAsPackedTrianglesGivesTheManifestVolume) {
    const auto files = corpus_binary_stls();
    ASSERT_GE(files.size(), 15u) << "corpus missing at " << kCorpus;
    for (const CorpusStl& c : files) {
        SCOPED_TRACE(c.path);
        const std::vector<float> tri = read_binary_stl_triangles((kCorpus / c.path).string());
        const LoadedMesh full = read_mesh_file((kCorpus / c.path).string());
        ASSERT_EQ(tri.size(), 3 * full.vertices_in_file);  // 9 per triangle either way
        // The same coordinates (the Mesh's are the floats widened, welded).
        ASSERT_EQ(full.mesh.indices.size(), tri.size() / 3);
        for (std::size_t i = 0; i < full.mesh.indices.size(); ++i)
            for (std::size_t k = 0; k < 3; ++k)
                ASSERT_EQ(static_cast<double>(tri[3 * i + k]),
                          full.mesh.positions[3 * std::size_t{full.mesh.indices[i]} + k])
                    << i;
        EXPECT_EQ(bits(soup_volume(packed_triangles(tri))), bits(c.volume));
    }
}

}  // namespace
