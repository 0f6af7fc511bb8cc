// A material law added from outside Densify's sources, through the
// extension point of doc/architecture.md ("A material law"): a class
// derived from Material, registered with register_material_model() under a
// name of its own and then chosen by Material/Model like the built-in
// models. The toy law is a compressible neo-Hookean solid,
// P = mu (F - F^-T) + lambda ln J F^-T, without history.
// 1. Its tangent A = dP/dF equals central differences at a general F.
// 2. Through the whole program: the sphere of the Hertz test (d = 2.5 mm,
//    Sn's E and nu, coarse mesh) pressed between two punches ends near the
//    punch force of the built-in finite-strain elastic model (Hencky). The
//    two laws agree to first order in the strain, so the forces differ
//    relatively by at most about the contact strain (some per cent under
//    the contact at 0.024 mm): within 2 %, and a quarter of the stroke at
//    least halves the difference.
#include <deal.II/base/mpi.h>

#include <densify/material/factory.h>
#include <densify/simulator.h>

#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

namespace
{
  using namespace densify;

  /// The compressible neo-Hookean law.
  class ToyNeoHooke : public Material
  {
  public:
    ToyNeoHooke(const double       E,
                const double       nu,
                const double       rho,
                const std::string &label)
      : E(E)
      , mu(E / (2. * (1. + nu)))
      , lambda(E * nu / ((1. + nu) * (1. - 2. * nu)))
      , rho(rho)
      , label(label)
    {}

    std::string
    name() const override
    {
      return "toy neo-Hookean (" + label + ")";
    }

    void
    evaluate(const Tensor<2, 3> &F,
             const MaterialState * /*committed*/,
             MaterialState * /*trial*/,
             Tensor<2, 3> &P,
             Tensor<4, 3> &A) const override
    {
      const Tensor<2, 3> Fi   = invert(F);
      const double       logJ = std::log(determinant(F));
      P = mu * (F - transpose(Fi)) + lambda * logJ * transpose(Fi);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = 0; l < 3; ++l)
              A[i][j][k][l] = (i == k && j == l ? mu : 0.) +
                              (mu - lambda * logJ) * Fi[j][k] * Fi[l][i] +
                              lambda * Fi[j][i] * Fi[l][k];
    }

    double
    youngs_modulus() const override
    {
      return E;
    }

    double
    p_wave_modulus() const override
    {
      return lambda + 2. * mu;
    }

    double
    bulk_modulus() const override
    {
      return lambda + 2. / 3. * mu;
    }

    double
    density() const override
    {
      return rho;
    }

  private:
    const double      E, mu, lambda, rho;
    const std::string label;
  };



  /// The toy's tangent against central differences of its stress.
  double
  tangent_error()
  {
    const ToyNeoHooke  law(43120., 0.33, 7.29e-9, "Sn");
    const Tensor<2, 3> F0(
      {{1.05, 0.1, -0.02}, {0.03, 0.93, 0.07}, {-0.04, 0.02, 1.1}});
    Tensor<2, 3> P0, P1, P2;
    Tensor<4, 3> A, unused;
    law.evaluate(F0, nullptr, nullptr, P0, A);
    double error = 0;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int l = 0; l < 3; ++l)
        {
          Tensor<2, 3> dF;
          dF[k][l] = 1e-6;
          law.evaluate(F0 + dF, nullptr, nullptr, P1, unused);
          law.evaluate(F0 - dF, nullptr, nullptr, P2, unused);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              error = std::max(error,
                               std::abs((P1[i][j] - P2[i][j]) / 2e-6 -
                                        A[i][j][k][l]));
        }
    return error / A.norm();
  }



  /// The upper punch force of the coarse Hertz sphere pressed by
  /// @p stroke (mm) with the Material/Model @p model at finite strain.
  double
  punch_force(const std::string &model, const std::string &stroke)
  {
    Parameters       parameters;
    ParameterHandler prm;
    testing::read_scene(
      parameters,
      prm,
      "hertz.prm",
      testing::coarse_sphere("output_" + model.substr(0, 3),
                             {"Material/Model=" + model,
                              "Material/Finite strain=true",
                              "Mesh/Refinement directions=0,"
                              "0,1; 0,0,-1",
                              "Mesh/Refined element size=0.1",
                              "Tools/Upper punch/Displacement history=0:0, 1:" +
                                stroke}));
    Simulator simulator(parameters, MPI_COMM_WORLD, false);
    simulator.run();
    return simulator.statistics().back().upper_punch_force;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  register_material_model(
    {"toy neo-Hookean",
     false,
     [](const J2Parameters &constants, const MaterialParameters &) {
       return std::make_shared<ToyNeoHooke>(constants.E,
                                            constants.nu,
                                            constants.density,
                                            constants.label);
     }});
  std::ostringstream out;
  out << "toy law: tangent vs central differences "
      << testing::yes(tangent_error() < 1e-7) << "; Material/Model offers it: "
      << testing::yes(material_model_names() ==
                      "elastic|J2 plasticity|toy neo-Hookean")
      << std::endl;
  // the two laws differ at second order in the strain, so their forces
  // differ relatively by at most about the strain, which falls at least as
  // the square root of the stroke: a quarter of the stroke at least halves
  // the difference (a ratio of 0.13 measured on this mesh)
  std::vector<double> difference;
  for (const std::string stroke : {"0.024", "0.006"})
    {
      const double hencky = punch_force("elastic", stroke);
      const double toy    = punch_force("toy neo-Hookean", stroke);
      difference.push_back((toy - hencky) / hencky);
      std::cerr << std::setprecision(8) << "stroke " << stroke
                << " mm: F_upper Hencky " << hencky << " N, toy " << toy
                << " N, difference " << difference.back() << std::endl;
    }
  const double ratio = difference[1] / difference[0];
  out << "Hertz sphere: toy against Hencky within 2 % at 0.024 mm "
      << testing::yes(std::abs(difference[0]) < 0.02)
      << ", a quarter of the stroke at least halves the difference (ratio 0 "
      << "to 0.5: " << testing::yes(ratio > 0. && ratio < 0.5) << ")"
      << std::endl;
  if (root)
    std::cout << out.str();
  return testing::all_passed ? 0 : 1;
}
