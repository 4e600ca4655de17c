#pragma once
// Poisson-disk samples of koala.obj (seed 1), cached in the build folder's bench-cache/ so that
// the benchmarks that only read them (Delaunay, Dey-Zhao) do not pay for the sampling each run.
// The cache is a plain binary file: count, points, normals.
#include <medax/io.hpp>
#include <medax/services/poisson.hpp>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>

namespace medax::bench {

inline const SurfaceMesh& koala(const std::filesystem::path& meshes_dir) {
  static const SurfaceMesh mesh = read_mesh(meshes_dir / "koala.obj");
  return mesh;
}

inline const OrientedSamples& koala_samples(const std::filesystem::path& meshes_dir, std::size_t n) {
  static std::map<std::size_t, OrientedSamples> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  std::filesystem::create_directories(MEDAX_BENCH_CACHE_DIR);
  const std::filesystem::path file =
      std::filesystem::path(MEDAX_BENCH_CACHE_DIR) / ("koala_poisson_" + std::to_string(n) + ".bin");
  OrientedSamples s;
  std::ifstream in(file, std::ios::binary);
  std::uint64_t count = 0;
  if (in && in.read(reinterpret_cast<char*>(&count), sizeof count) && count == n) {
    s.points.resize(n);
    s.normals.resize(n);
    in.read(reinterpret_cast<char*>(s.points.data()), static_cast<std::streamsize>(n * sizeof(Vec3)));
    in.read(reinterpret_cast<char*>(s.normals.data()), static_cast<std::streamsize>(n * sizeof(Vec3)));
  }
  if (!in || count != n) {
    const auto t0 = std::chrono::steady_clock::now();
    std::mt19937_64 rng(1);
    s = services::sample_poisson_count(koala(meshes_dir), n, rng);
    std::cerr << "sampled " << n << " Poisson-disk points of koala in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s (cached in "
              << file << ")\n";
    std::ofstream out(file, std::ios::binary);
    count = n;
    out.write(reinterpret_cast<const char*>(&count), sizeof count);
    out.write(reinterpret_cast<const char*>(s.points.data()), static_cast<std::streamsize>(n * sizeof(Vec3)));
    out.write(reinterpret_cast<const char*>(s.normals.data()), static_cast<std::streamsize>(n * sizeof(Vec3)));
  }
  return cache.emplace(n, std::move(s)).first->second;
}

}  // namespace medax::bench
