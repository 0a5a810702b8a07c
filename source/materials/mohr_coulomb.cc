#include <mpm/core/input_error.h>
#include <mpm/materials/mohr_coulomb.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mpm
{
  void
  MohrCoulomb::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mohr-Coulomb");
    prm.declare_entry("Cohesion", "0", Patterns::Double(0.),
                      "Cohesion c [Pa].");
    prm.declare_entry("Friction angle", "30", Patterns::Double(0., 89.),
                      "Friction angle phi [degrees].");
    prm.declare_entry("Dilatancy angle", "0", Patterns::Double(0., 89.),
                      "Dilatancy angle psi [degrees], at most phi; psi < "
                      "phi is non-associated flow.");
    prm.leave_subsection();
  }



  MohrCoulomb::MohrCoulomb(ParameterHandler & prm,
                           const std::string &name,
                           const std::string &section_path)
    : HenckyPlasticity(prm, name, section_path)
  {
    prm.enter_subsection("Mohr-Coulomb");
    cohesion         = prm.get_double("Cohesion");
    const double phi = prm.get_double("Friction angle") * numbers::PI / 180.;
    const double psi = prm.get_double("Dilatancy angle") * numbers::PI / 180.;
    prm.leave_subsection();
    if (psi > phi)
      throw InputError(section_path +
                       "/Mohr-Coulomb/Dilatancy angle must not exceed the "
                       "Friction angle.");
    if (phi == 0. && cohesion == 0.)
      throw InputError(section_path +
                       "/Mohr-Coulomb: with Friction angle = 0 the Cohesion "
                       "must be positive (the material would have no "
                       "strength).");
    k = (1. + std::sin(phi)) / (1. - std::sin(phi));
    m = (1. + std::sin(psi)) / (1. - std::sin(psi));
  }



  double
  MohrCoulomb::yield_function(const Tensor<1, 3> &tau, double) const
  {
    const double largest  = std::max({tau[0], tau[1], tau[2]});
    const double smallest = std::min({tau[0], tau[1], tau[2]});
    return k * largest - smallest - 2. * cohesion * std::sqrt(k);
  }



  HenckyPlasticity::Return
  MohrCoulomb::return_to_yield_surface(const Tensor<1, 3> &trial_tau,
                                       double) const
  {
    const Tensor<2, 3> D = principal_stiffness();
    Return             r;
    r.tau     = trial_tau;
    r.tangent = D;
    if (yield_function(trial_tau, 0.) <= 0.)
      return r;

    // Work in the ordered frame: sigma_1 >= sigma_2 >= sigma_3.
    std::array<unsigned int, 3> order = {{0, 1, 2}};
    std::sort(order.begin(), order.end(), [&](unsigned int a, unsigned int b) {
      return trial_tau[a] > trial_tau[b];
    });
    Tensor<1, 3> sigma_trial;
    for (unsigned int i = 0; i < 3; ++i)
      sigma_trial[i] = trial_tau[order[i]];

    const double sigma_c = 2. * cohesion * std::sqrt(k);
    // Normals of the yield planes and plastic potentials in the ordered
    // frame: the main plane, and the second plane of each edge.
    const Tensor<1, 3> a_main({k, 0., -1.}), b_main({m, 0., -1.});
    const Tensor<1, 3> a_first({0., k, -1.}), b_first({0., m, -1.});
    const Tensor<1, 3> a_second({k, -1., 0.}), b_second({m, -1., 0.});
    const double       tolerance = 1e-12 * (std::abs(sigma_c) +
                                      sigma_trial.norm() + 1.);
    auto ordered = [&](const Tensor<1, 3> &s) {
      return s[0] >= s[1] - tolerance && s[1] >= s[2] - tolerance;
    };

    Tensor<1, 3> sigma;
    Tensor<2, 3> tangent;
    Tensor<1, 3> plastic_strain;
    bool         done = false;

    // 1. The plane.
    {
      const Tensor<1, 3> Db    = D * b_main;
      const double       gamma = (a_main * sigma_trial - sigma_c) / (a_main * Db);
      sigma                    = sigma_trial - gamma * Db;
      if (ordered(sigma))
        {
          tangent = D - outer_product(Db, D * a_main) / (a_main * Db);
          plastic_strain = gamma * b_main;
          done           = true;
        }
    }
    // 2. An edge, with two multipliers: the one that the plane return
    //    crossed.
    if (!done)
      {
        const bool         first_edge = sigma[1] > sigma[0];
        const Tensor<1, 3> a2 = first_edge ? a_first : a_second;
        const Tensor<1, 3> b2 = first_edge ? b_first : b_second;
        const std::array<Tensor<1, 3>, 2> A = {{a_main, a2}};
        const std::array<Tensor<1, 3>, 2> Bd = {{D * b_main, D * b2}};
        double M[2][2];
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            M[i][j] = A[i] * Bd[j];
        const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
        const double f1  = a_main * sigma_trial - sigma_c;
        const double f2  = a2 * sigma_trial - sigma_c;
        const double g1  = (M[1][1] * f1 - M[0][1] * f2) / det;
        const double g2  = (M[0][0] * f2 - M[1][0] * f1) / det;
        const Tensor<1, 3> s = sigma_trial - g1 * Bd[0] - g2 * Bd[1];
        if (g1 >= 0. && g2 >= 0. && ordered(s))
          {
            sigma = s;
            // D - D B (A^T D B)^-1 A^T D.
            const double inv[2][2] = {{M[1][1] / det, -M[0][1] / det},
                                      {-M[1][0] / det, M[0][0] / det}};
            tangent = D;
            for (unsigned int i = 0; i < 2; ++i)
              for (unsigned int j = 0; j < 2; ++j)
                tangent -= inv[i][j] * outer_product(Bd[i], D * A[j]);
            plastic_strain = g1 * b_main + g2 * b2;
            done           = true;
          }
      }
    // 3. The apex (phi > 0 only: for Tresca the edges always hold).
    if (!done)
      {
        AssertThrow(k > 1., ExcInternalError());
        const double apex = sigma_c / (k - 1.);
        sigma             = Tensor<1, 3>({apex, apex, apex});
        tangent           = Tensor<2, 3>();
        plastic_strain    = invert(D) * (sigma_trial - sigma);
      }

    for (unsigned int i = 0; i < 3; ++i)
      {
        r.tau[order[i]] = sigma[i];
        for (unsigned int j = 0; j < 3; ++j)
          r.tangent[order[i]][order[j]] = tangent[i][j];
      }
    r.plastic_strain_increment =
      std::sqrt(2. / 3. * (plastic_strain * plastic_strain));
    return r;
  }
} // namespace mpm
