#include <mpm/boundary/rigid_contact.h>

#include <algorithm>

namespace mpm
{
  template <int dim>
  const CoulombContact<dim> &
  RigidContact<dim>::act(const unsigned int    node,
                         const unsigned int    slot,
                         const unsigned int    surface,
                         const Tensor<1, dim> &relative,
                         const Tensor<1, dim> &into_surface,
                         const double          friction,
                         const double          mass,
                         const double          dt) const
  {
    Reaction reaction;
    reaction.node    = node;
    reaction.slot    = slot;
    reaction.surface = surface;
    reaction.law = CoulombContact<dim>(relative, into_surface, friction, mass, dt);
    if (reaction.law.active)
      {
        reaction.normal     = reaction.law.normal_force;
        reaction.tangential = reaction.law.tangential_force;
        reaction.force      = reaction.law.force();
      }
    first_reaction.emplace(slot, reactions.size());
    reactions.push_back(reaction);
    return reactions.back().law;
  }



  template <int dim>
  void
  RigidContact<dim>::record(const unsigned int    node,
                            const unsigned int    surface,
                            const Tensor<1, dim> &outward,
                            const Tensor<1, dim> &force) const
  {
    Reaction reaction;
    reaction.node       = node;
    reaction.slot       = node;
    reaction.surface    = surface;
    reaction.normal     = force * outward;
    reaction.tangential = force - reaction.normal * outward;
    reaction.force      = force;
    reactions.push_back(reaction);
  }



  template <int dim>
  void
  RigidContact<dim>::follow_change(const unsigned int slot,
                                   double *           change) const
  {
    const auto first = first_reaction.find(slot);
    if (first == first_reaction.end())
      return;
    for (unsigned int r = first->second;
         r < reactions.size() && reactions[r].slot == slot;
         ++r)
      {
        Reaction &reaction  = reactions[r];
        reaction.law        = reaction.law.follow_change(change);
        reaction.normal     = reaction.law.normal_force;
        reaction.tangential = reaction.law.tangential_force;
        reaction.force      = reaction.law.force();
      }
  }



  template <int dim>
  std::vector<const typename RigidContact<dim>::Reaction *>
  RigidContact<dim>::owned_reactions() const
  {
    const unsigned int n_owned = grid.node_partitioner()->locally_owned_size();
    std::vector<const Reaction *> owned;
    for (const Reaction &reaction : reactions)
      if (reaction.node < n_owned)
        owned.push_back(&reaction);
    return owned;
  }



  template <int dim>
  std::vector<const typename RigidContact<dim>::Reaction *>
  RigidContact<dim>::owned_reactions_by_surface() const
  {
    std::vector<const Reaction *> owned = owned_reactions();
    std::stable_sort(owned.begin(),
                     owned.end(),
                     [](const Reaction *a, const Reaction *b) {
                       return a->surface < b->surface;
                     });
    return owned;
  }



  template class RigidContact<2>;
  template class RigidContact<3>;
} // namespace mpm
