// polyvol/chain_io.hpp — reading boundary chains (.chain, qhull's output)
// and plane polygons (chain.hpp) from files. Readers throw ReadError
// (io.hpp) with the file, the 1-based line and what was expected.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "polyvol/chain.hpp"
#include "polyvol/io.hpp"

namespace polyvol {

enum class ChainFormat { chain, qhull };

// "chain", "qhull".
std::string_view chain_format_name(ChainFormat f);

struct LoadedChain {
    Chain chain;
    ChainFormat format = ChainFormat::chain;
    // qhull input: facets whose listed order was reversed to face outward, and
    // facets the interior point could not orient (flat ones: their
    // determinant is within rounding of zero) — these keep qhull's order;
    // orient_chain (simplicial.hpp) orients them by their neighbours.
    std::size_t facets_reoriented = 0;
    std::size_t facets_undecided = 0;
    std::size_t qhull_facets = 0;          // facets as listed (before fanning, n = 3 only)
    std::vector<std::string> notes;        // e.g. "qhull-fanned-facets(6)"
};

// Reads a .chain file or qhull's OFF output, chosen by content: after
// comments, a first line of three integers is .chain, of one integer qhull.
// "-" reads standard input; gzip-compressed input is decompressed first.
LoadedChain read_chain_file(const std::string& path);
LoadedChain read_chain_memory(std::span<const std::byte> data, const std::string& name);

// Reads the polygon text format (one loop per line).
Polygons read_polygons_file(const std::string& path);
Polygons read_polygons_memory(std::span<const std::byte> data, const std::string& name);

}  // namespace polyvol
