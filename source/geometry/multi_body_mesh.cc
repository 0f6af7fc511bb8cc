// One triangulation of all particles; no vertex shared between particles.
#include <deal.II/base/numbers.h>

#include <deal.II/grid/tria_description.h>

#include <densify/geometry/multi_body_mesh.h>

#include <map>
#include <sstream>
#include <stdexcept>

namespace densify
{
  void
  build_multi_body_triangulation(const std::vector<Particle> &particles,
                                 const SphereMeshSpec        &spec,
                                 Triangulation<3>            &tria)
  {
    if (particles.empty())
      throw std::runtime_error(
        "multi-body mesh: there are no particles to mesh");
    if (particles.size() >=
        static_cast<std::size_t>(numbers::invalid_material_id))
      throw std::runtime_error(
        "multi-body mesh: too many particles for one material id each");

    // One mesh per distinct sphere diameter, centred at the origin; one per
    // particle of another shape (in its orientation).
    std::map<double, TetMesh>       meshes;
    std::map<unsigned int, TetMesh> shaped;
    std::size_t                     n_vertices = 0, n_cells = 0;
    for (unsigned int i = 0; i < particles.size(); ++i)
      {
        const double diameter = particles[i].diameter;
        if (!(diameter > 0.))
          {
            std::ostringstream s;
            s << "particle " << i << ": diameter " << diameter
              << " mm must be > 0 (Particles/Diameters or the particle file)";
            throw std::runtime_error(s.str());
          }
        const TetMesh *mesh = nullptr;
        if (particles[i].shape != ParticleShape::sphere)
          mesh =
            &shaped.emplace(i, mesh_particle(particles[i], spec)).first->second;
        else
          {
            auto it = meshes.find(diameter);
            if (it == meshes.end())
              it = meshes.emplace(diameter, mesh_particle(particles[i], spec))
                     .first;
            mesh = &it->second;
          }
        n_vertices += mesh->vertices.size();
        n_cells += mesh->cells.size();
      }

    // Concatenate translated copies. Every particle gets its own vertices,
    // even where two particles touch: create_triangulation() only connects
    // cells through shared vertex indices, never through coordinates.
    std::vector<Point<3>>    vertices;
    std::vector<CellData<3>> cells;
    vertices.reserve(n_vertices);
    cells.reserve(n_cells);
    for (unsigned int i = 0; i < particles.size(); ++i)
      {
        const TetMesh     &mesh = particles[i].shape != ParticleShape::sphere ?
                                    shaped.at(i) :
                                    meshes.at(particles[i].diameter);
        const unsigned int offset = vertices.size();
        const Tensor<1, 3> shift  = particles[i].centre;
        for (const Point<3> &v : mesh.vertices)
          vertices.push_back(v + shift);
        for (const auto &tet : mesh.cells)
          {
            CellData<3> cell(4);
            for (unsigned int v = 0; v < 4; ++v)
              cell.vertices[v] = offset + tet[v];
            cell.material_id = i;
            cells.push_back(cell);
          }
      }

    // No boundary description: every boundary face gets boundary id 0.
    tria.create_triangulation(vertices, cells, SubCellData());
  }
} // namespace densify
