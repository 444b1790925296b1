// Intel Embree's single-ray traversal on the rays irsig's traversal example writes
// (crates/tracer/examples/traversal.rs): the same triangles, the same rays, one thread.
//
//   g++ -O2 -o embree_rays scripts/bench/embree_rays.cpp -lembree3
//   ./embree_rays DIR ROUNDS
//
// Reads DIR/triangles.bin and DIR/rays-{scanline,tiles}.bin (little-endian: a u32 count,
// then 9 or 6 f32 per record) and prints, per ray order, the fastest of ROUNDS passes of
// rtcIntersect1 in ns per ray, the number of rays that hit, and the scene's build time
// (rtcCommitScene, Embree's default build quality, all threads).
#include <embree3/rtcore.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

static std::vector<float> read_records(const std::string& path, unsigned per_record, uint32_t& count) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    std::fprintf(stderr, "%s: cannot open\n", path.c_str());
    std::exit(1);
  }
  if (std::fread(&count, 4, 1, f) != 1) {
    std::fprintf(stderr, "%s: no count\n", path.c_str());
    std::exit(1);
  }
  std::vector<float> data(static_cast<size_t>(count) * per_record);
  if (std::fread(data.data(), 4, data.size(), f) != data.size()) {
    std::fprintf(stderr, "%s: shorter than its count\n", path.c_str());
    std::exit(1);
  }
  std::fclose(f);
  return data;
}

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: embree_rays DIR [ROUNDS]\n");
    return 2;
  }
  std::string dir = argv[1];
  int rounds = argc > 2 ? std::atoi(argv[2]) : 5;
  uint32_t ntris = 0;
  std::vector<float> tris = read_records(dir + "/triangles.bin", 9, ntris);

  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  float* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * static_cast<size_t>(ntris)));
  unsigned* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), ntris));
  for (size_t i = 0; i < tris.size(); ++i) vertices[i] = tris[i];
  for (size_t i = 0; i < 3 * static_cast<size_t>(ntris); ++i) indices[i] = static_cast<unsigned>(i);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  auto t0 = std::chrono::steady_clock::now();
  rtcCommitScene(scene);
  double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("embree %d.%d.%d: %u triangles, build %.3f s\n", RTC_VERSION_MAJOR, RTC_VERSION_MINOR,
              RTC_VERSION_PATCH, ntris, build_s);
  std::printf("| order | embree rtcIntersect1 (ns/ray) | hits |\n| --- | ---: | ---: |\n");

  for (const char* order : {"scanline", "tiles"}) {
    uint32_t nrays = 0;
    std::vector<float> rays = read_records(dir + "/rays-" + order + ".bin", 6, nrays);
    double best = std::numeric_limits<double>::infinity();
    uint64_t hits = 0;
    RTCIntersectContext context;
    for (int round = 0; round < rounds; ++round) {
      // One untimed pass first, as irsig's side does.
      for (int timed = 0; timed < 2; ++timed) {
        auto start = std::chrono::steady_clock::now();
        uint64_t h = 0;
        for (uint32_t i = 0; i < nrays; ++i) {
          const float* r = &rays[6 * static_cast<size_t>(i)];
          RTCRayHit rh;
          rh.ray.org_x = r[0];
          rh.ray.org_y = r[1];
          rh.ray.org_z = r[2];
          rh.ray.dir_x = r[3];
          rh.ray.dir_y = r[4];
          rh.ray.dir_z = r[5];
          rh.ray.tnear = 0.0f;
          rh.ray.tfar = std::numeric_limits<float>::infinity();
          rh.ray.mask = 0xFFFFFFFFu;
          rh.ray.flags = 0;
          rh.ray.time = 0.0f;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          rtcInitIntersectContext(&context);
          rtcIntersect1(scene, &context, &rh);
          if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) ++h;
        }
        double ns = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() * 1e9 / nrays;
        if (timed) {
          best = std::fmin(best, ns);
          hits = h;
        }
      }
    }
    std::printf("| %s | %.0f | %llu |\n", order, best, static_cast<unsigned long long>(hits));
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return 0;
}
