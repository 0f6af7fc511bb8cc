// Helpers shared by the test programs: reading a scene from prm/ with
// overrides.
#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <densify/parameters.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace densify
{
  namespace testing
  {
    /// A pseudo-random number in [-1, 1] from the 64-bit linear congruential
    /// generator @p state: the same sequence with every compiler and
    /// standard library (std::uniform_real_distribution's is not).
    inline double
    uniform(std::uint64_t &state)
    {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(state >> 11) * 0x1.0p-52 - 1.;
    }

    /// I + a matrix of entries uniform in [-@p size, @p size] (uniform()).
    inline Tensor<2, 3>
    random_gradient(std::uint64_t &state, const double size)
    {
      Tensor<2, 3> F = unit_symmetric_tensor<3>();
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          F[i][j] += size * uniform(state);
      return F;
    }

    /// Set when any check fails, so that the test also fails by exit code.
    inline bool all_passed = true;

    /// "yes" or "no", remembering a "no" in all_passed.
    inline std::string
    yes(const bool ok)
    {
      all_passed = all_passed && ok;
      return ok ? "yes" : "no";
    }

    /**
     * "yes" if @p value lies within the relative @p tolerance of
     * @p reference (remembering a "no" in all_passed). For results that
     * round-off moves by more than the 1e-4 numdiff reads (a path-dependent
     * law's answer depends on the increments a solve happens to take): the
     * test prints the verdict, the value goes to the log.
     */
    inline std::string
    near(const double value, const double reference, const double tolerance)
    {
      return yes(std::abs(value - reference) <=
                 tolerance * std::abs(reference));
    }

    /// Write @p text to the file @p name in the working directory.
    inline void
    write_file(const std::string &name, const std::string &text)
    {
      std::ofstream out(name);
      out << text;
    }

    /// The source directory (from the DENSIFY_SOURCE_DIR environment variable).
    inline std::string
    source_dir()
    {
      const char *dir = std::getenv("DENSIFY_SOURCE_DIR");
      return dir != nullptr ? dir : ".";
    }

    /**
     * Overrides that shrink prm/hertz.prm to a coarse uniform P1 mesh without
     * graphics, writing into @p directory, followed by @p extra.
     */
    inline std::vector<std::string>
    coarse_sphere(const std::string &directory, std::vector<std::string> extra)
    {
      std::vector<std::string> overrides = {"Output/Directory=" + directory,
                                            "Output/Interval=0",
                                            "Mesh/Polynomial degree=1",
                                            "Mesh/Element size=0.4",
                                            "Mesh/Refinement directions="};
      overrides.insert(overrides.end(), extra.begin(), extra.end());
      return overrides;
    }

    /**
     * Overrides that make prm/hertz.prm the coarse sphere of
     * friction_sliding: refined at its poles, pressed by 0.03 mm between
     * two punches with friction 0.2 in t = 0..1, then pulled along x by the
     * body force @p b (MPa/mm = N/mm^3), ramped in t = 1..2; 6 load steps, up
     * to 3 cut-backs; writing into @p directory, followed by @p extra.
     */
    inline std::vector<std::string>
    pulled_sphere(const std::string       &directory,
                  const double             b,
                  std::vector<std::string> extra)
    {
      char force[64];
      std::snprintf(force, sizeof(force), "%.17g,0,0", b);
      std::vector<std::string> overrides = {
        "Mesh/Refinement directions=0,0,1; 0,0,-1",
        "Mesh/Refined element size=0.1",
        "Contact/Friction coefficient=0.2",
        "Tools/Upper punch/Displacement history=0:0, 1:0.03",
        std::string("Particles/Body force=") + force,
        "Particles/Body force history=0:0, 1:0, 2:1",
        "Time stepping/End time=2",
        "Time stepping/Number of steps=6",
        "Time stepping/Maximum cut-backs=3"};
      overrides.insert(overrides.end(), extra.begin(), extra.end());
      return coarse_sphere(directory, overrides);
    }

    /**
     * Overrides that turn prm/hertz.prm into two spheres (d = 2.5) stacked
     * on the z axis, touching at one point, with a uniform mesh of
     * polynomial @p degree and element size 0.3, without output files.
     */
    inline std::vector<std::string>
    two_stacked_spheres(const unsigned int degree)
    {
      return {"Output/Directory=output",
              "Output/Interval=0",
              "Mesh/Polynomial degree=" + std::to_string(degree),
              "Mesh/Element size=0.3",
              "Mesh/Refinement directions=",
              "Particles/Centres=0,0,1.25; 0,0,3.75",
              "Particles/Diameters=2.5"};
    }

    /// The contact points densify uses for P1: the corners of the reference
    /// triangle with weights area/3.
    inline dealii::Quadrature<2>
    facet_corners()
    {
      return dealii::Quadrature<2>(
        std::vector<dealii::Point<2>>{dealii::Point<2>(0, 0),
                                      dealii::Point<2>(1, 0),
                                      dealii::Point<2>(0, 1)},
        std::vector<double>(3, 1. / 6.));
    }

    /// The floating-particle scene: a pressed sphere (d = 2.5) and one
    /// (d = 1.5) that touches nothing, pressed by 0.1 mm in two steps.
    inline std::vector<std::string>
    floating_scene()
    {
      return {"Particles/Centres=0,0,1.25; 4,0,1.25",
              "Particles/Diameters=2.5, 1.5",
              "Tools/Upper punch/Displacement history=0:0, 1:0.1",
              "Time stepping/Number of steps=2"};
    }

    /// Read prm/@p scene from the source tree into @p parameters, then apply
    /// @p overrides ("Sub/Name=value").
    inline void
    read_scene(Parameters                     &parameters,
               ParameterHandler               &prm,
               const std::string              &scene,
               const std::vector<std::string> &overrides)
    {
      parameters.declare(prm);
      read_parameters(prm, source_dir() + "/prm/" + scene, overrides);
    }

    /// A fully ghosted copy of @p owned.
    inline dealii::TrilinosWrappers::MPI::Vector
    ghosted(const dealii::DoFHandler<3>                 &dof_handler,
            const dealii::TrilinosWrappers::MPI::Vector &owned)
    {
      dealii::TrilinosWrappers::MPI::Vector all(
        dof_handler.locally_owned_dofs(),
        dealii::complete_index_set(dof_handler.n_dofs()),
        dof_handler.get_communicator());
      all = owned;
      return all;
    }

    /// A displacement of linear elements, fully ghosted: @p shift for the
    /// particles from number @p first_moved on, plus on all a small smooth
    /// field 1e-3 sin(2 x_d + x_{d+1}) (mm).
    inline dealii::TrilinosWrappers::MPI::Vector
    smooth_displacement(const dealii::DoFHandler<3>     &dof_handler,
                        const dealii::Tensor<1, 3>      &shift,
                        const dealii::types::material_id first_moved = 0)
    {
      dealii::TrilinosWrappers::MPI::Vector owned(
        dof_handler.locally_owned_dofs(), dof_handler.get_communicator());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            {
              const dealii::Point<3> &x = cell->vertex(v);
              for (unsigned int d = 0; d < 3; ++d)
                owned(cell->vertex_dof_index(v, d)) =
                  (cell->material_id() >= first_moved ? shift[d] : 0.) +
                  1e-3 * std::sin(2. * x[d] + x[(d + 1) % 3]);
            }
      owned.compress(dealii::VectorOperation::insert);
      return ghosted(dof_handler, owned);
    }
  } // namespace testing
} // namespace densify
