#include "io/text.hpp"

#include <algorithm>
#include <utility>

namespace polyvol::io::text {

void add_note(LoadedMesh& out, std::string note) {
    if (std::find(out.notes.begin(), out.notes.end(), note) == out.notes.end())
        out.notes.push_back(std::move(note));
}

}  // namespace polyvol::io::text
