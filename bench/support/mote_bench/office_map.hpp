#pragma once
/// \file
/// The generated office map the benchmarks share (bench_maps, bench_raycast): written once per
/// process into a temporary folder as a PGM with its map_server YAML, so every benchmark that
/// needs a large map reads the same one through the real loader.

#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace mote::bench {

/// Writes text to path through a file of this process's own, renamed into place (atomic on one
/// file system): two benchmark processes that write the same map at once never read a half-
/// written one. Throws std::runtime_error when the file cannot be written.
inline void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::path part = path;
  part += ".part" + std::to_string(::getpid());
  {
    std::ofstream out(part, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + part.string());
  }
  std::filesystem::rename(part, path);
}

/// A size x size office-like PGM: free floor inside an unknown margin, random walls and
/// rectangular rooms (0 = occupied, 254 = free, 205 = unknown), plus its map_server YAML.
inline std::filesystem::path write_office_map(int size) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mote_bench_maps_" + std::to_string(size));
  std::filesystem::create_directories(dir);
  const auto n = static_cast<std::size_t>(size);
  std::vector<unsigned char> px(n * n, 205);
  const std::size_t margin = n / 20;
  for (std::size_t r = margin; r < n - margin; ++r) {
    std::fill(px.begin() + static_cast<long>(r * n + margin),
              px.begin() + static_cast<long>(r * n + n - margin), 254);
  }
  std::mt19937 rng(42);
  std::uniform_int_distribution<std::size_t> pos(margin, n - margin - 1);
  auto wall = [&](std::size_t r0, std::size_t c0, std::size_t r1, std::size_t c1) {
    for (std::size_t r = r0; r <= std::min(r1, n - 1); ++r)
      for (std::size_t c = c0; c <= std::min(c1, n - 1); ++c) px[r * n + c] = 0;
  };
  for (int k = 0; k < size / 8; ++k) {
    const std::size_t r = pos(rng), c = pos(rng), len = pos(rng) / 8;
    if (k % 3 == 0) {  // a room outline
      wall(r, c, r + 1, c + len), wall(r + len, c, r + len + 1, c + len);
      wall(r, c, r + len, c + 1), wall(r, c + len, r + len + 1, c + len + 1);
    } else if (k % 3 == 1) {
      wall(r, c, r + 2, c + len);
    } else {
      wall(r, c, r + len, c + 2);
    }
  }
  write_file_atomically(dir / "map.pgm", "P5\n" + std::to_string(size) + ' ' +
                                             std::to_string(size) + "\n255\n" +
                                             std::string(px.begin(), px.end()));
  write_file_atomically(dir / "map.yaml",
                        "image: map.pgm\nresolution: 0.05\norigin: [-100.0, -100.0, 0.0]\n"
                        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  return dir / "map.yaml";
}

}  // namespace mote::bench
