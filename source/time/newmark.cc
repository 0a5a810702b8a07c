#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/time/newmark.h>

#include <string>

namespace mpm
{
  void
  Newmark::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newmark");
    prm.declare_entry("Bossak alpha", "0", Patterns::Double(-0.5, 0.),
                      "Bossak's alpha_B: the inertia is taken at "
                      "(1 - alpha_B) a_n+1 + alpha_B a_n, which damps high "
                      "frequencies. 0 is plain Newmark; -0.3 to -0.1 are "
                      "usual.");
    prm.declare_entry("Beta", "auto", Patterns::Anything(),
                      "Newmark beta. auto: (1 - alpha_B)^2 / 4, that is 0.25 "
                      "for plain Newmark (the trapezoidal rule, no numerical "
                      "damping).");
    prm.declare_entry("Gamma", "auto", Patterns::Anything(),
                      "Newmark gamma. auto: 1/2 - alpha_B.");
    prm.declare_entry("Mass matrix", "consistent",
                      Patterns::Selection("consistent|lumped"),
                      "consistent: the inertia m_p a(x_p) of each point, "
                      "with mass m_p N_i N_k (Iaconeta et al. eq. 30). "
                      "lumped: the nodal masses sum_p m_p N_i on the "
                      "diagonal, as the explicit scheme uses. A node reached "
                      "by only one or two points has a nearly singular "
                      "consistent mass and stiffness; the lumped mass keeps "
                      "Newton robust on fast-moving bodies with thin "
                      "surface cells.");
    prm.leave_subsection();
  }



  Newmark::Newmark(ParameterHandler &prm, const bool dynamic)
  {
    prm.enter_subsection("Newmark");
    bossak_alpha = prm.get_double("Bossak alpha");
    auto number_or_auto = [&](const std::string &entry, const double automatic) {
      const std::string text = prm.get(entry);
      if (text == "auto")
        return automatic;
      return parse_number(text,
                          "Newmark/" + entry + " = '" + text +
                            "' must be a number or 'auto'.");
    };
    beta =
      number_or_auto("Beta", 0.25 * (1. - bossak_alpha) * (1. - bossak_alpha));
    gamma = number_or_auto("Gamma", 0.5 - bossak_alpha);
    lumped_mass = prm.get("Mass matrix") == "lumped";
    prm.leave_subsection();
    if (dynamic && !(beta > 0.))
      throw InputError("Newmark/Beta must be positive for the implicit "
                       "scheme.");
  }
} // namespace mpm
