#include <deal.II/base/mpi.h>

#include <mpm/assembly/field_contact.h>
#include <mpm/base/gathered_csv.h>
#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/boundary/coulomb_contact.h>

#include <algorithm>
#include <cmath>

namespace mpm
{
  template <int dim>
  void
  FieldContact<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry(
      "Pairs", "", Patterns::Anything(),
      "How the contact groups of the bodies (Bodies/<name>/Contact group) "
      "meet, pair by pair: 'wall-fill: 0.5, wall-soil: 0.6, pile-soil: "
      "tied', each a Coulomb coefficient (0 or more, inf: no sliding) or "
      "tied (the two move together where they touch, in tension too). A "
      "pair not named meets with the Default friction. Bodies in one group "
      "share a velocity field, as if glued where they touch.");
    prm.declare_entry("Default friction", "0", Patterns::Anything(),
                      "The Coulomb coefficient of the pairs of groups that "
                      "Pairs does not name (0: frictionless, inf: no "
                      "sliding).");
    prm.declare_entry(
      "Normal", "separating gradient",
      Patterns::Selection("separating gradient|maximum volume gradient|"
                          "volume gradient difference"),
      "The normal between two groups at a node, from their volume "
      "gradients sum V_p grad N over each group's points near it. "
      "separating gradient: the gradient of either group along which the "
      "two groups' surfaces near the node are further apart (a separating "
      "axis: a gradient tilted by a body's corner, or by the other face "
      "of a body that a wide support sees, makes the bodies overlap along "
      "it); the default. maximum volume gradient: the larger gradient "
      "(CB-Geo's rule), which tilts where a body's corner is near the "
      "node. volume gradient difference: both weigh in.");
    prm.declare_entry(
      "Gap tolerance", "0", Patterns::Double(0.),
      "Two groups touch at a node where they approach and their surfaces, "
      "measured from the points near the node, will be less than this "
      "apart at the end of the step, as a fraction of the smallest cell. A "
      "point's surface lies half its deformed box from it.");
    prm.leave_subsection();
  }



  template <int dim>
  FieldContact<dim>::FieldContact(ParameterHandler &             prm,
                                  const std::vector<Body<dim>> &bodies,
                                  const Grid<dim> &              grid)
    : grid(grid)
  {
    for (const Body<dim> &body : bodies)
      {
        const std::string &group = body.contact_group();
        if (group.empty() ||
            group.find_first_of("-:, \t") != std::string::npos)
          throw InputError("Bodies/" + body.name() + "/Contact group = '" +
                           group + "' must be a name without '-', ':', ',' "
                           "or spaces.");
        const auto found =
          std::find(group_names.begin(), group_names.end(), group);
        body_fields.push_back(found - group_names.begin());
        if (found == group_names.end())
          group_names.push_back(group);
      }
    if (group_names.empty())
      group_names.push_back("default");
    if (n_groups() == 1)
      body_fields.clear();

    prm.enter_subsection("Contact");
    PairLaw default_law;
    default_law.friction =
      parse_friction_coefficient(prm.get("Default friction"),
                                 "Contact/Default friction");
    parse_pairs(prm.get("Pairs"), default_law);
    const std::string rule = prm.get("Normal");
    normal_rule = rule == "separating gradient" ?
                    NormalRule::separating_gradient :
                    rule == "maximum volume gradient" ?
                    NormalRule::largest_gradient :
                    NormalRule::gradient_difference;
    gap_tolerance = prm.get_double("Gap tolerance");
    prm.leave_subsection();

    recorded.assign(n_groups() * n_groups() * (dim + 2), 0.);
    grid_changed = grid.changed.connect([this]() {
      slot_gradients.clear();
      shared.clear();
      shared_index.clear();
    });
  }



  template <int dim>
  void
  FieldContact<dim>::parse_pairs(const std::string &text,
                                 const PairLaw &    default_law)
  {
    pair_laws.assign(n_groups() * n_groups(), default_law);
    std::vector<bool> named(pair_laws.size(), false);
    const std::string entry = "Contact/Pairs";
    for (const std::string &item : Utilities::split_string_list(text, ','))
      {
        const std::string::size_type colon = item.find(':');
        const std::string::size_type dash  = item.find('-');
        if (colon == std::string::npos || dash == std::string::npos ||
            dash > colon)
          throw InputError(entry + ": '" + item +
                           "' must be 'group-group: friction' or "
                           "'group-group: tied'.");
        unsigned int groups[2];
        const std::string names[2] = {
          Utilities::trim(item.substr(0, dash)),
          Utilities::trim(item.substr(dash + 1, colon - dash - 1))};
        for (unsigned int i = 0; i < 2; ++i)
          {
            const auto found =
              std::find(group_names.begin(), group_names.end(), names[i]);
            if (found == group_names.end())
              {
                std::string known;
                for (const std::string &name : group_names)
                  known += (known.empty() ? "" : ", ") + name;
                throw InputError(entry + ": '" + item + "' names the group '" +
                                 names[i] + "', which no body is in (the "
                                 "bodies' Contact groups: " + known + ").");
              }
            groups[i] = found - group_names.begin();
          }
        if (groups[0] == groups[1])
          throw InputError(entry + ": '" + item + "' pairs a group with "
                           "itself; the bodies of one group share a field.");
        const unsigned int pair = pair_index(std::min(groups[0], groups[1]),
                                             std::max(groups[0], groups[1]));
        if (named[pair])
          throw InputError(entry + ": the pair in '" + item +
                           "' is named twice.");
        named[pair]                = true;
        const std::string value    = Utilities::trim(item.substr(colon + 1));
        pair_laws[pair].tied       = value == "tied";
        pair_laws[pair].friction   = pair_laws[pair].tied ?
                                       0. :
                                       parse_friction_coefficient(
                                         value,
                                         entry + ": the friction of '" +
                                           names[0] + "-" + names[1] + "'");
      }
  }



  template <int dim>
  void
  FieldContact<dim>::check_scene(const SceneChoices &choices) const
  {
    if (n_groups() > 1 && !choices.explicit_steps())
      throw InputError(
        "The bodies are in " + std::to_string(n_groups()) +
        " Contact groups, and contact between bodies runs with Time "
        "stepping/Scheme = explicit: the quasi-static and Newmark schemes "
        "solve one displacement field for all bodies. Put every body in "
        "one group (the default), or use the explicit scheme.");
  }



  template <int dim>
  void
  FieldContact<dim>::begin_projection(const GridNodes<dim> &nodes)
  {
    for (const unsigned int slot : nodes.slots_to_solve())
      if ((slot + 1) * dim <= slot_gradients.size())
        std::fill_n(slot_gradients.begin() + slot * dim, dim, 0.);
  }



  template <int dim>
  void
  FieldContact<dim>::find_normals(const GridNodes<dim> &nodes)
  {
    using NodalLayout = typename GridNodes<dim>::NodalLayout;
    for (const unsigned int node : shared)
      shared_index[node] = none;
    shared_index.resize(grid.n_nodes(), none);
    shared = nodes.shared_nodes();
    const unsigned int K = n_groups();
    slot_gradients.resize(std::max<std::size_t>(slot_gradients.size(),
                                                nodes.n_slots() * dim),
                          0.);

    gradients.assign(shared.size() * K * dim, 0.);
    for (unsigned int k = 0; k < shared.size(); ++k)
      {
        shared_index[shared[k]] = k;
        for (unsigned int field = 0; field < K; ++field)
          {
            const unsigned int slot = nodes.slot(shared[k], field);
            if (slot != GridNodes<dim>::no_slot)
              std::copy_n(slot_gradients.begin() + slot * dim,
                          dim,
                          gradients.begin() + (k * K + field) * dim);
          }
      }
    nodes.combine_over_ranks(shared, gradients, K * dim, false);

    lower_field.assign(shared.size(), none);
    upper_field.assign(shared.size(), none);
    candidates.assign(2 * shared.size(), Tensor<1, dim>());
    for (unsigned int k = 0; k < shared.size(); ++k)
      {
        unsigned int n_with_mass = 0;
        for (unsigned int field = 0; field < K; ++field)
          {
            const unsigned int slot = nodes.slot(shared[k], field);
            if (slot == GridNodes<dim>::no_slot ||
                !(nodes.values_of(slot)[NodalLayout::mass] > 0.))
              continue;
            (n_with_mass == 0 ? lower_field[k] : upper_field[k]) = field;
            ++n_with_mass;
          }
        if (n_with_mass != 2)
          lower_field[k] = upper_field[k] = none;
        else
          for (unsigned int c = 0; c < 2; ++c)
            candidates[2 * k + c] =
              normal(k, lower_field[k], upper_field[k], c);
      }
    surfaces.assign(4 * shared.size(),
                    -std::numeric_limits<double>::infinity());
  }



  template <int dim>
  Tensor<1, dim>
  FieldContact<dim>::normal(const unsigned int k,
                            const unsigned int a,
                            const unsigned int b,
                            const unsigned int candidate) const
  {
    const Tensor<1, dim> g_a = gradient(k, a), g_b = gradient(k, b);
    // sum V_p grad N_i(x_p) points from a field's points to the node: at
    // the field's surface, out of it. From A to B: g_a, or -g_b.
    Tensor<1, dim> n;
    switch (normal_rule)
      {
        case NormalRule::separating_gradient:
          n = candidate == 0 ? g_a : -g_b;
          break;
        case NormalRule::largest_gradient:
          n = g_a.norm() >= g_b.norm() ? g_a : -g_b;
          break;
        case NormalRule::gradient_difference:
          n = g_a - g_b;
          break;
      }
    const double length = n.norm();
    return length > 0. ? n / length : Tensor<1, dim>();
  }



  template <int dim>
  void
  FieldContact<dim>::add_point(const unsigned int             field,
                               const Support<dim> &           support,
                               const Point<dim> &             x,
                               const ArrayView<const double> &p)
  {
    for (unsigned int i = 0; i < support.n_nodes; ++i)
      {
        const unsigned int k = shared_index[support.nodes[i]];
        if (k == none || (field != lower_field[k] && field != upper_field[k]))
          continue;
        for (unsigned int candidate = 0; candidate < 2; ++candidate)
          {
            const Tensor<1, dim> &n = candidates[2 * k + candidate];
            // Half the extent along n of the point's box, whose edges
            // l_d e_d have become l_d F e_d.
            double reach = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              {
                double along = 0.;
                for (unsigned int c = 0; c < dim; ++c)
                  along +=
                    n[c] * p[Layout::deformation_gradient + c * dim + d];
                reach += 0.5 * p[Layout::reference_size + d] * std::abs(along);
              }
            const double s     = x * n;
            double *     ends  = &surfaces[4 * k + 2 * candidate];
            if (field == lower_field[k])
              ends[0] = std::max(ends[0], s + reach);
            else
              ends[1] = std::max(ends[1], reach - s);
          }
      }
  }



  template <int dim>
  void
  FieldContact<dim>::finish_surfaces(const GridNodes<dim> &nodes)
  {
    nodes.combine_over_ranks(shared, surfaces, 4, true);
    // The candidate along which the surfaces are further apart: a normal
    // tilted off the face the bodies meet at makes them overlap along it.
    normals.assign(shared.size(), Tensor<1, dim>());
    distances.assign(shared.size(), 0.);
    for (unsigned int k = 0; k < shared.size(); ++k)
      if (lower_field[k] != none)
        {
          double apart[2];
          for (unsigned int c = 0; c < 2; ++c)
            apart[c] = candidates[2 * k + c].norm_square() > 0. ?
                         -surfaces[4 * k + 2 * c] - surfaces[4 * k + 2 * c + 1] :
                         -std::numeric_limits<double>::infinity();
          const unsigned int c = apart[1] > apart[0] ? 1 : 0;
          normals[k]           = candidates[2 * k + c];
          distances[k]         = apart[c];
        }
  }



  template <int dim>
  void
  FieldContact<dim>::couple(GridNodes<dim> &nodes,
                            const double    dt,
                            const bool      end_of_step)
  {
    using NodalLayout          = typename GridNodes<dim>::NodalLayout;
    const unsigned int K       = n_groups();
    const unsigned int n_owned = grid.node_partitioner()->locally_owned_size();
    const double       gap     = gap_tolerance * grid.minimum_cell_size();
    if (end_of_step)
      {
        std::fill(recorded.begin(), recorded.end(), 0.);
        node_forces.resize(n_groups() * n_groups());
        for (auto &rows : node_forces)
          rows.clear();
      }

    // A field's velocity as the law sees it, and its write-back.
    const auto velocity_of = [&](const double *v) {
      Tensor<1, dim> u;
      for (unsigned int d = 0; d < dim; ++d)
        u[d] = v[NodalLayout::velocity + d] +
               (end_of_step ? dt * v[NodalLayout::force + d] : 0.);
      return u;
    };
    const auto set_velocity = [&](double *v, const Tensor<1, dim> &u) {
      for (unsigned int d = 0; d < dim; ++d)
        if (end_of_step)
          v[NodalLayout::force + d] =
            (u[d] - v[NodalLayout::velocity + d]) / dt;
        else
          v[NodalLayout::velocity + d] = u[d];
    };

    std::vector<unsigned int> fields;
    for (unsigned int k = 0; k < shared.size(); ++k)
      {
        const unsigned int node = shared[k];
        fields.clear();
        for (unsigned int field = 0; field < K; ++field)
          {
            const unsigned int slot = nodes.slot(node, field);
            if (slot != GridNodes<dim>::no_slot &&
                nodes.values_of(slot)[NodalLayout::mass] > 0.)
              fields.push_back(field);
          }
        const bool two_fields = lower_field[k] != none;
        for (unsigned int i = 0; i < fields.size(); ++i)
          for (unsigned int j = i + 1; j < fields.size(); ++j)
            {
              const unsigned int a = fields[i], b = fields[j];
              const PairLaw &    law = pair_laws[pair_index(a, b)];
              // Where three fields meet, no surfaces decide: the larger
              // gradient's normal.
              const Tensor<1, dim> n =
                two_fields ?
                  normals[k] :
                  normal(k,
                         a,
                         b,
                         normal_rule == NormalRule::separating_gradient ?
                           (gradient(k, a).norm() >= gradient(k, b).norm() ?
                              0 :
                              1) :
                           0);
              if (n.norm_square() == 0.)
                continue;
              double *values_a = nodes.values_of(nodes.slot(node, a));
              double *values_b = nodes.values_of(nodes.slot(node, b));
              const double         m_a = values_a[NodalLayout::mass];
              const double         m_b = values_b[NodalLayout::mass];
              const Tensor<1, dim> v_a = velocity_of(values_a);
              const Tensor<1, dim> v_b = velocity_of(values_b);
              const double approach = (v_a - v_b) * n;
              if (!law.tied && !(approach > 0.))
                continue;
              if (two_fields)
                {
                  // The surfaces' distance at the end of the step.
                  const double apart = distances[k] - dt * approach;
                  if (!(apart < gap))
                    continue;
                }
              const Tensor<1, dim> centre =
                (m_a * v_a + m_b * v_b) / (m_a + m_b);
              const Tensor<1, dim> relative = v_a - centre;
              Tensor<1, dim>       end;
              if (!law.tied)
                {
                  // Before the first step (dt = 0) only velocities are
                  // constrained, and the law's forces are not read.
                  const CoulombContact<dim> coulomb(
                    relative, n, law.friction, m_a, dt > 0. ? dt : 1.);
                  if (!coulomb.active)
                    continue;
                  end = coulomb.end;
                }
              set_velocity(values_a, centre + end);
              set_velocity(values_b, centre - (m_a / m_b) * end);
              if (end_of_step && node < n_owned)
                {
                  // The force of A on B, m_a (relative - end) / dt.
                  const Tensor<1, dim> force = m_a * (relative - end) / dt;
                  double *r = &recorded[pair_index(a, b) * (dim + 2)];
                  for (unsigned int d = 0; d < dim; ++d)
                    r[d] += force[d];
                  const double normal_part = force * n;
                  const double tangential_part =
                    (force - normal_part * n).norm();
                  r[dim] += normal_part;
                  r[dim + 1] += tangential_part;
                  std::array<double, dim + 2> row;
                  for (unsigned int d = 0; d < dim; ++d)
                    row[d] = grid.node_position(node)[d];
                  row[dim]     = normal_part;
                  row[dim + 1] = tangential_part;
                  node_forces[pair_index(a, b)].push_back(row);
                }
            }
      }
  }



  template <int dim>
  std::vector<std::string>
  FieldContact<dim>::force_names() const
  {
    const char *             axes = "xyz";
    std::vector<std::string> names;
    for (unsigned int a = 0; a < n_groups(); ++a)
      for (unsigned int b = a + 1; b < n_groups(); ++b)
        {
          const std::string pair = group_names[a] + "_on_" + group_names[b];
          for (unsigned int d = 0; d < dim; ++d)
            names.push_back(pair + "_force_" + axes[d]);
          names.push_back(pair + "_normal_force");
          names.push_back(pair + "_tangential_force");
        }
    return names;
  }



  template <int dim>
  std::vector<double>
  FieldContact<dim>::forces() const
  {
    std::vector<double> values;
    for (unsigned int a = 0; a < n_groups(); ++a)
      for (unsigned int b = a + 1; b < n_groups(); ++b)
        values.insert(values.end(),
                      recorded.begin() + pair_index(a, b) * (dim + 2),
                      recorded.begin() + (pair_index(a, b) + 1) * (dim + 2));
    Utilities::MPI::sum(values, grid.get_communicator(), values);
    return values;
  }



  template <int dim>
  void
  FieldContact<dim>::write_tractions(const std::string &directory,
                                     const unsigned int step) const
  {
    const std::vector<std::array<double, dim + 2>> none_recorded;
    for (unsigned int a = 0; a < n_groups(); ++a)
      for (unsigned int b = a + 1; b < n_groups(); ++b)
        {
          const unsigned int pair = pair_index(a, b);
          write_gathered_csv(grid.get_communicator(),
                             pair < node_forces.size() ? node_forces[pair] :
                                                         none_recorded,
                             step_csv_name(directory,
                                           group_names[a] + "_on_" +
                                             group_names[b] + "_forces",
                                           step),
                             coordinate_columns<dim>() +
                               "normal_force,tangential_force");
        }
  }



  template class FieldContact<2>;
  template class FieldContact<3>;
} // namespace mpm
