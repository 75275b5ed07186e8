// load_sim_setup: turns a scene into the simulator's input, reading the files it names (head
// mesh, strand file); body_params and projector_options: what the renderer draws and projects.
// See scene_setup.hpp.
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "apps/render/scene_setup.hpp"
#include "io/hair_file.hpp"
#include "io/hair_json.hpp"
#include "io/scene_mesh.hpp"
#include "sim/clumps.hpp"
#include "sim/hair_model.hpp"

namespace wisp::render {
namespace {

// Every point within sim::kMaxWorldMetres of the head, else an error naming the fields that put
// it there: huge coordinates scaled up stay finite here but overflow in the simulation.
void check_reach(const Eigen::Vector3d& p, const std::string& what, const std::string& fields) {
  if (p.allFinite() && p.norm() <= sim::kMaxWorldMetres) return;
  char where[64];
  std::snprintf(where, sizeof where, "%.3g", p.norm());
  throw std::invalid_argument(fields + ": " + what + " lies " + where +
                              " m from the head (at most " +
                              std::to_string(int(sim::kMaxWorldMetres)) + " m)");
}

// The guides of a dense model (hair.guides > 0): its strands clustered into clumps, each clump's
// medoid resampled to hair.segments (0 keeps its points) and kept off the head, with the clump's
// width along it.
void add_clump_guides(const std::vector<sim::Polyline>& strands, const io::Scene& scene,
                      sim::SimSetup& setup) {
  const sim::HairParams& h = scene.hair;
  sim::ClumpOptions options;
  options.count = h.guides;
  options.seed = h.seed;
  const sim::Clumps clumps = sim::cluster_strands(strands, options);
  double samples = 0;
  for (int i : clumps.guide) samples += h.segments > 0 ? h.segments + 1 : double(strands[i].size());
  sim::check_budget(samples, scene.motion, scene.sim);
  std::vector<std::vector<int>> members(clumps.guide.size());
  for (std::size_t i = 0; i < strands.size(); ++i) members[clumps.clump_of[i]].push_back(int(i));
  const sim::HeadShape head(setup.head);
  for (std::size_t c = 0; c < clumps.guide.size(); ++c) {
    const sim::Polyline& medoid = strands[clumps.guide[c]];
    sim::Polyline guide = h.segments > 0 ? sim::resample(medoid, h.segments) : medoid;
    sim::clear_head(guide, head, scene.sim.collision_margin + 0.002);
    setup.widths.push_back(sim::clump_width(guide, strands, members[c]));
    setup.rest.push_back(std::move(guide));
  }
}

}  // namespace

sim::SimSetup load_sim_setup(const io::Scene& scene) {
  const std::string file = scene.path.string();
  sim::TriangleMesh mesh;
  if (scene.head.shape == sim::HeadKind::Mesh) {
    try {
      mesh = io::read_obj(scene.head.mesh);
    } catch (const std::exception& e) {
      throw std::runtime_error(file + ": head.mesh: " + e.what());
    }
  }
  try {
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      Eigen::Vector3d& v = mesh.vertices[i];
      v = v * scene.head.mesh_scale + scene.head.mesh_offset;
      check_reach(v, "vertex " + std::to_string(i + 1) + " of " + scene.head.mesh.string(),
                  "head.mesh_scale");
    }
    if (scene.hair.source == sim::HairSource::Procedural && scene.hair.guides > 0) {
      sim::SimSetup setup = sim::make_base_setup(scene.head, scene.motion, scene.sim, mesh);
      const sim::HeadShape head(setup.head);
      add_clump_guides(sim::generate_hair(scene.hair, head, scene.sim.collision_margin + 0.002),
                       scene, setup);
      return setup;
    }
    if (scene.hair.source == sim::HairSource::Procedural) {
      sim::check_budget(double(scene.hair.count) * (scene.hair.segments + 1), scene.motion,
                        scene.sim);
      return sim::make_setup(scene.head, scene.hair, scene.motion, scene.sim, mesh);
    }

    sim::SimSetup setup = sim::make_base_setup(scene.head, scene.motion, scene.sim, mesh);
    std::vector<sim::Polyline> strands;
    try {
      strands = scene.hair.source == sim::HairSource::Json
                    ? io::read_strands_json(scene.hair.file)
                    : io::read_hair_file(scene.hair.file).strands;
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("hair.file: ") + e.what());
    }
    // File coordinates to head-local metres; strands of a single point are dropped.
    const sim::HairParams& h = scene.hair;
    std::vector<sim::Polyline> usable;
    for (std::size_t i = 0; i < strands.size(); ++i) {
      sim::Polyline& s = strands[i];
      if (s.size() < 2) continue;
      for (auto& p : s) {
        p *= h.file_scale;
        if (h.file_z_up) p = Eigen::Vector3d(p.x(), p.z(), -p.y());
        p += h.file_offset;
        check_reach(p, "strand " + std::to_string(i) + " of " + h.file.string(), "hair.file_scale");
      }
      usable.push_back(std::move(s));
    }
    if (usable.empty())
      throw std::runtime_error("hair.file: " + h.file.string() + " has no strand with 2 points");
    if (h.guides > 0) {
      add_clump_guides(usable, scene, setup);
      return setup;
    }
    const std::vector<int> guides = sim::select_guides(usable, h.count);
    double samples = 0;
    for (int i : guides) samples += h.segments > 0 ? h.segments + 1 : double(usable[i].size());
    sim::check_budget(samples, scene.motion, scene.sim);
    const sim::HeadShape head(setup.head);
    for (int i : guides) {
      sim::Polyline guide = h.segments > 0 ? sim::resample(usable[i], h.segments) : usable[i];
      sim::clear_head(guide, head, scene.sim.collision_margin + 0.002);
      setup.rest.push_back(std::move(guide));
    }
    return setup;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(file + ": " + e.what());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(file + ": " + e.what());
  }
}

sim::BodyParams body_params(const io::Scene& scene) {
  sim::BodyParams body = sim::body_params(scene.head);
  body.head = scene.render.body;
  body.neck = body.torso = scene.render.body && scene.render.torso;
  body.face = scene.render.face;
  return body;
}

sim::ProjectorOptions projector_options(const io::Scene& scene) {
  sim::ProjectorOptions options;
  options.light_dir = scene.light_dir;
  const sim::BodyParams body = body_params(scene);
  if (body.neck || body.torso) options.body = std::make_shared<const sim::BodyParams>(body);
  return options;
}

}  // namespace wisp::render
