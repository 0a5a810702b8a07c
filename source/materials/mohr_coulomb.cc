#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/materials/mohr_coulomb.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace mpm
{
  void
  MohrCoulomb::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mohr-Coulomb");
    prm.declare_entry("Cohesion", "0", Patterns::Double(0.),
                      "Cohesion c [Pa] (the peak value with softening).");
    prm.declare_entry("Friction angle", "30", Patterns::Double(0., 89.),
                      "Friction angle phi [degrees] (the peak value with "
                      "softening).");
    prm.declare_entry("Dilatancy angle", "0", Patterns::Double(0., 89.),
                      "Dilatancy angle psi [degrees], at most phi; psi < "
                      "phi is non-associated flow. With softening it is "
                      "capped at the current friction angle.");
    prm.declare_entry("Softening plastic strain", "0", Patterns::Double(0.),
                      "Equivalent plastic strain at which c and phi reach "
                      "their residual values, falling linearly from the "
                      "peak; 0 means no softening.");
    prm.declare_entry("Residual cohesion", "peak", Patterns::Anything(),
                      "Cohesion after softening [Pa], at most the Cohesion; "
                      "'peak' keeps the Cohesion. Read only with a "
                      "Softening plastic strain > 0.");
    prm.declare_entry("Residual friction angle", "peak", Patterns::Anything(),
                      "Friction angle after softening [degrees], at most "
                      "the Friction angle; 'peak' keeps the Friction angle. "
                      "Read only with a Softening plastic strain > 0.");
    prm.declare_entry("Tension cut-off", "false", Patterns::Bool(),
                      "Limit the largest principal stress to the Tensile "
                      "strength (Rankine plane, associated flow).");
    prm.declare_entry("Tensile strength", "0", Patterns::Double(0.),
                      "Tensile strength t [Pa] of the cut-off, at most "
                      "c cot(phi), where Mohr-Coulomb itself has its apex. "
                      "It does not soften; once softening brings the apex "
                      "below t, the apex limits the tension. Plastic strain "
                      "at the cut-off counts towards softening too.");
    prm.leave_subsection();
  }



  MohrCoulomb::MohrCoulomb(ParameterHandler & prm,
                           const std::string &name,
                           const std::string &section_path)
    : HenckyPlasticity(prm, name, section_path)
  {
    const double      degree = numbers::PI / 180.;
    const std::string here   = section_path + "/Mohr-Coulomb/";
    // A residual value: 'peak' or a number, not below zero.
    auto residual = [&](const std::string &entry, const double peak) {
      const std::string text = prm.get(entry);
      if (text == "peak")
        return peak;
      const double value = parse_point<1>(text, here + entry)[0];
      if (!(value >= 0.))
        throw InputError(here + entry + " = " + text +
                         " must be 'peak' or a number >= 0.");
      return value;
    };
    prm.enter_subsection("Mohr-Coulomb");
    peak_cohesion            = prm.get_double("Cohesion");
    peak_friction_angle      = prm.get_double("Friction angle") * degree;
    dilatancy_angle          = prm.get_double("Dilatancy angle") * degree;
    softening_plastic_strain = prm.get_double("Softening plastic strain");
    residual_cohesion        = peak_cohesion;
    residual_friction_angle  = peak_friction_angle;
    if (softening_plastic_strain > 0.)
      {
        residual_cohesion = residual("Residual cohesion", peak_cohesion);
        residual_friction_angle =
          residual("Residual friction angle", peak_friction_angle / degree) *
          degree;
      }
    tension_cut_off  = prm.get_bool("Tension cut-off");
    tensile_strength = prm.get_double("Tensile strength");
    prm.leave_subsection();

    if (dilatancy_angle > peak_friction_angle)
      throw InputError(here + "Dilatancy angle must not exceed the Friction "
                              "angle.");
    if (peak_friction_angle == 0. && peak_cohesion == 0.)
      throw InputError(here + "with Friction angle = 0 the Cohesion must be "
                              "positive (the material would have no "
                              "strength).");
    if (residual_cohesion > peak_cohesion ||
        residual_friction_angle > peak_friction_angle)
      throw InputError(here + "Residual cohesion and Residual friction angle "
                              "must not exceed the Cohesion and the Friction "
                              "angle: softening only lowers the strength.");
    if (residual_friction_angle == 0. && residual_cohesion == 0.)
      throw InputError(here + "with Residual friction angle = 0 the Residual "
                              "cohesion must be positive (the softened "
                              "material would have no strength).");
    if (tension_cut_off && peak_friction_angle > 0. &&
        tensile_strength > peak_cohesion / std::tan(peak_friction_angle))
      {
        std::ostringstream message;
        message << here << "Tensile strength = " << tensile_strength
                << " exceeds c cot(phi) = "
                << peak_cohesion / std::tan(peak_friction_angle)
                << ", the apex of the Mohr-Coulomb surface: the cut-off "
                   "would never act.";
        throw InputError(message.str());
      }
    peak_planes = planes_of({peak_cohesion, peak_friction_angle});

    // The sets of planes a return may rest on, fewest first: one, then the
    // lines of two, the points of three. Without a tension cut-off the
    // stress can rest only on the main plane 0 (k s_1 - s_3 = sigma_c), on
    // its edges with plane 1 (s_1 = s_2) or plane 2 (s_2 = s_3), or on all
    // three: plane 1 or 2 alone, or the two together, leave plane 0
    // violated unless two stresses are equal, where the edge holds them
    // too. The explicit scheme returns most points of a flowing granular
    // body every step, so the sets that cannot hold are not listed.
    const unsigned int n_planes = peak_planes.size();
    if (n_planes == 3)
      active_sets = {{{{0, 0, 0}}, 1}, {{{0, 1, 0}}, 2}, {{{0, 2, 0}}, 2},
                     {{{0, 1, 2}}, 3}};
    else
      {
        for (unsigned int i = 0; i < n_planes; ++i)
          active_sets.push_back({{{i, 0, 0}}, 1});
        for (unsigned int i = 0; i < n_planes; ++i)
          for (unsigned int j = i + 1; j < n_planes; ++j)
            active_sets.push_back({{{i, j, 0}}, 2});
        for (unsigned int i = 0; i < n_planes; ++i)
          for (unsigned int j = i + 1; j < n_planes; ++j)
            for (unsigned int l = j + 1; l < n_planes; ++l)
              active_sets.push_back({{{i, j, l}}, 3});
      }
    for (const ActiveSet &set : active_sets)
      peak_inverses.push_back(invert_set(peak_planes, set));
  }



  std::pair<double, double>
  MohrCoulomb::strength(const double plastic_strain) const
  {
    const double s =
      softening_plastic_strain > 0. ?
        std::min(plastic_strain / softening_plastic_strain, 1.) :
        0.;
    return {peak_cohesion + s * (residual_cohesion - peak_cohesion),
            peak_friction_angle +
              s * (residual_friction_angle - peak_friction_angle)};
  }



  MohrCoulomb::Planes
  MohrCoulomb::planes(const double plastic_strain) const
  {
    if (softening_plastic_strain == 0. || !(plastic_strain > 0.))
      return peak_planes;
    return planes_of(strength(plastic_strain));
  }



  MohrCoulomb::Plane::Plane(const Tensor<1, 3> &a,
                            const Tensor<1, 3> &b,
                            const double        r,
                            const Tensor<2, 3> &D)
    : a(a)
    , b(b)
    , r(r)
    , Db(D * b)
    , Da(D * a)
    , a_norm(a.norm())
    , scale(a_norm * Db.norm())
  {}



  MohrCoulomb::Planes
  MohrCoulomb::planes_of(const std::pair<double, double> &strength) const
  {
    const auto [c, phi] = strength;
    const double psi    = std::min(dilatancy_angle, phi);
    const double k      = (1. + std::sin(phi)) / (1. - std::sin(phi));
    const double m      = (1. + std::sin(psi)) / (1. - std::sin(psi));
    const double sigma_c = 2. * c * std::sqrt(k);
    const Tensor<2, 3> &D = principal_stiffness;
    Planes result;
    result.emplace_back(Tensor<1, 3>({k, 0., -1.}),
                        Tensor<1, 3>({m, 0., -1.}),
                        sigma_c,
                        D);
    result.emplace_back(Tensor<1, 3>({0., k, -1.}),
                        Tensor<1, 3>({0., m, -1.}),
                        sigma_c,
                        D);
    result.emplace_back(Tensor<1, 3>({k, -1., 0.}),
                        Tensor<1, 3>({m, -1., 0.}),
                        sigma_c,
                        D);
    if (tension_cut_off)
      for (unsigned int i = 0; i < 3; ++i)
        {
          Tensor<1, 3> e;
          e[i] = 1.;
          result.emplace_back(e, e, tensile_strength, D);
        }
    return result;
  }



  double
  MohrCoulomb::yield_function(const Tensor<1, 3> &tau,
                              const double        plastic_strain) const
  {
    return largest_violation(planes(plastic_strain), tau);
  }



  double
  MohrCoulomb::largest_violation(const Planes &      surfaces,
                                 const Tensor<1, 3> &tau)
  {
    Tensor<1, 3> sorted = tau;
    std::sort(&sorted[0], &sorted[0] + 3, std::greater<double>());
    double f = -std::numeric_limits<double>::max();
    for (const Plane &plane : surfaces)
      f = std::max(f, plane.a * sorted - plane.r);
    return f;
  }



  MohrCoulomb::SetInverse
  MohrCoulomb::invert_set(const Planes &surfaces, const ActiveSet &set)
  {
    // Inverted in closed form for n = 1 and 2.
    const std::array<unsigned int, 3> &active = set.planes;
    const unsigned int                  n      = set.n;
    double                              M[3][3];
    double                              scale = 1.;
    for (unsigned int i = 0; i < n; ++i)
      {
        scale *= surfaces[active[i]].scale;
        for (unsigned int j = 0; j < n; ++j)
          M[i][j] = surfaces[active[i]].a * surfaces[active[j]].Db;
      }
    SetInverse result;
    double     det;
    if (n == 1)
      {
        det                    = M[0][0];
        result.M_inverse[0][0] = 1. / det;
      }
    else if (n == 2)
      {
        det                    = M[0][0] * M[1][1] - M[0][1] * M[1][0];
        result.M_inverse[0][0] = M[1][1] / det;
        result.M_inverse[0][1] = -M[0][1] / det;
        result.M_inverse[1][0] = -M[1][0] / det;
        result.M_inverse[1][1] = M[0][0] / det;
      }
    else
      {
        Tensor<2, 3> full;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            full[i][j] = M[i][j];
        det = determinant(full);
        if (det != 0.)
          full = invert(full);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            result.M_inverse[i][j] = full[i][j];
      }
    result.singular = std::abs(det) <= 1e-10 * scale;
    return result;
  }



  HenckyPlasticity::Return
  MohrCoulomb::return_to_yield_surface(const Tensor<1, 3> &trial_tau,
                                       const double        plastic_strain,
                                       const bool with_tangent) const
  {
    // Without softening the peak planes themselves, not a copy.
    Planes        softened;
    const Planes &surfaces =
      softening_plastic_strain == 0. || !(plastic_strain > 0.) ?
        peak_planes :
        (softened = planes_of(strength(plastic_strain)));
    Return r;
    r.tau = trial_tau;
    if (with_tangent)
      r.tangent = principal_stiffness;

    // Work in the ordered frame: sigma_1 >= sigma_2 >= sigma_3 (as
    // largest_violation() does), sorted once here by insertion, which
    // keeps equal stresses in their order.
    std::array<unsigned int, 3> order = {{0, 1, 2}};
    if (trial_tau[1] > trial_tau[0])
      std::swap(order[0], order[1]);
    if (trial_tau[2] > trial_tau[order[1]])
      {
        order[2] = order[1];
        order[1] = 2;
        if (trial_tau[2] > trial_tau[order[0]])
          std::swap(order[0], order[1]);
      }
    const Tensor<1, 3> sigma_trial({trial_tau[order[0]],
                                    trial_tau[order[1]],
                                    trial_tau[order[2]]});
    const unsigned int    n_planes = surfaces.size();
    std::array<double, 6> violation;
    double                largest  = -std::numeric_limits<double>::max();
    for (unsigned int i = 0; i < n_planes; ++i)
      {
        violation[i] = surfaces[i].a * sigma_trial - surfaces[i].r;
        largest      = std::max(largest, violation[i]);
      }
    if (largest <= 0.)
      return r;
    r.plastic = true;

    const double tolerance = 1e-12 * (surfaces[0].r + sigma_trial.norm() + 1.);
    // Without a cut-off every set tried below holds the main plane,
    // k s_1 - s_3 = sigma_c, and in the ordered frame that bounds the other
    // two (k s_2 - s_3 and k s_1 - s_2 are at most k s_1 - s_3, as k > 0):
    // the order is all that is left to check.
    const bool order_implies_planes = n_planes == 3;
    auto       admissible           = [&](const Tensor<1, 3> &s) {
      if (s[0] < s[1] - tolerance || s[1] < s[2] - tolerance)
        return false;
      if (order_implies_planes)
        return true;
      for (const Plane &plane : surfaces)
        // The round-off of a . s grows with |a| (k: 131 at phi = 80).
        if (plane.a * s - plane.r > tolerance * plane.a_norm)
          return false;
      return true;
    };

    Tensor<1, 3> sigma;
    Tensor<2, 3> tangent;
    Tensor<1, 3> plastic_strain_step;
    // The first set of planes whose return is admissible. Plain arrays and
    // the planes' own D b throughout, and no call per set: the explicit
    // scheme returns most points of a flowing granular body every step.
    bool done = false;
    const double p_wave_modulus = lambda + 2. * mu;
    const bool   peak           = &surfaces == &peak_planes;
    for (unsigned int k = 0; k < active_sets.size(); ++k)
      {
        const std::array<unsigned int, 3> &active = active_sets[k].planes;
        const unsigned int                  n      = active_sets[k].n;
        SetInverse                          softened_inverse;
        const SetInverse &                  inverse =
          peak ? peak_inverses[k] :
                 (softened_inverse = invert_set(surfaces, active_sets[k]));
        if (inverse.singular)
          continue;
        double       gamma[3];
        bool         flows = true;
        Tensor<1, 3> s     = sigma_trial;
        for (unsigned int i = 0; i < n; ++i)
          {
            gamma[i] = 0.;
            for (unsigned int j = 0; j < n; ++j)
              gamma[i] += inverse.M_inverse[i][j] * violation[active[j]];
            flows = flows && !(gamma[i] * p_wave_modulus < -tolerance);
            s -= gamma[i] * surfaces[active[i]].Db;
          }
        if (!flows || !admissible(s))
          continue;
        sigma               = s;
        plastic_strain_step = gamma[0] * surfaces[active[0]].b;
        for (unsigned int i = 1; i < n; ++i)
          plastic_strain_step += gamma[i] * surfaces[active[i]].b;
        if (with_tangent)
          {
            tangent = principal_stiffness;
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                tangent -= inverse.M_inverse[i][j] *
                           outer_product(surfaces[active[i]].Db,
                                         surfaces[active[j]].Da);
          }
        done = true;
        break;
      }
    // The apex, where the flow of the planes (psi = 0: deviatoric) cannot
    // reach: the stress goes to it and the rest of the step is plastic.
    if (!done)
      {
        const double k    = surfaces[0].a[0];
        const double apex = surfaces[0].r / (k - 1.);
        AssertThrow(k > 1. && !(tension_cut_off && tensile_strength < apex),
                    ExcMessage("Mohr-Coulomb: no return found for the trial "
                               "stress (" +
                               std::to_string(sigma_trial[0]) + ", " +
                               std::to_string(sigma_trial[1]) + ", " +
                               std::to_string(sigma_trial[2]) + ")."));
        sigma               = Tensor<1, 3>({apex, apex, apex});
        tangent             = Tensor<2, 3>();
        plastic_strain_step = principal_compliance * (sigma_trial - sigma);
      }

    for (unsigned int i = 0; i < 3; ++i)
      {
        r.tau[order[i]] = sigma[i];
        for (unsigned int j = 0; j < 3 && with_tangent; ++j)
          r.tangent[order[i]][order[j]] = tangent[i][j];
      }
    r.plastic_strain_increment =
      std::sqrt(2. / 3. * (plastic_strain_step * plastic_strain_step));
    return r;
  }



  MPM_REGISTER_MATERIAL(MohrCoulomb,
                        "Mohr-Coulomb",
                        "elastoplastic at finite strain with Hencky "
                        "elasticity (its subsection).",
                        &MohrCoulomb::declare_parameters)
} // namespace mpm
