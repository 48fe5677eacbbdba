// The baseline of docs/benchmarks.md: a plain single-threaded loop that mmaps
// a binary STL and sums det(a,b,c)/6 in double — what most tools do, minus
// their overheads. No accuracy guarantee (it loses digits far from the origin).
//   naive_stl_volume FILE.stl  ->  prints the volume and the seconds taken
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: naive_stl_volume FILE.stl\n");
        return 1;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const int fd = ::open(argv[1], O_RDONLY);
    struct stat st {};
    if (fd < 0 || ::fstat(fd, &st) != 0 || st.st_size < 84) {
        std::fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    const auto size = static_cast<std::size_t>(st.st_size);
    void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (map == MAP_FAILED) return 2;
    const auto* bytes = static_cast<const unsigned char*>(map);
    uint32_t n;
    std::memcpy(&n, bytes + 80, 4);
    if (84 + 50 * static_cast<std::size_t>(n) != size) return 2;
    double sum = 0;
    for (std::size_t t = 0; t < n; ++t) {
        float v[9];
        std::memcpy(v, bytes + 84 + 50 * t + 12, sizeof v);
        const double ax = v[0], ay = v[1], az = v[2], bx = v[3], by = v[4], bz = v[5], cx = v[6], cy = v[7], cz = v[8];
        sum += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
    }
    const double volume = sum / 6;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%.17g %.6f\n", volume, s);
    ::munmap(map, size);
    ::close(fd);
    return 0;
}
