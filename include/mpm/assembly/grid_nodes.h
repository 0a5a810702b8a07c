#ifndef mpm_assembly_grid_nodes_h
#define mpm_assembly_grid_nodes_h

#include <deal.II/base/partitioner.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/grid/grid.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The nodal values of the explicit scheme on the background grid, in K
   * velocity fields: one per contact group of bodies (K = 1: every body
   * in one field, which makes bodies that meet stick together). A field at
   * a node holds the lumped mass, the velocity (momentum while it is being
   * accumulated) and the force (acceleration after the nodal solve),
   * interleaved so that they sit together in memory.
   *
   * One field at one node is a slot. Field 0 is stored for every node, in
   * one vector distributed with the grid, and its slot is the node id; the
   * other fields are stored only at the nodes where they have points near,
   * in slots numbered from n_nodes() on, made by the projection that first
   * touches them (claim()). A slot's values start at values_of(slot).
   *
   * Only slots that carry material are touched: the active slots are
   * recorded while projecting and only those (plus the few nodes shared
   * with other ranks) are cleared before the next projection. An empty
   * region of the grid therefore costs nothing per step.
   */
  template <int dim>
  class GridNodes
  {
  public:
    /** The values of one field at one node. */
    struct NodalLayout
    {
      static constexpr unsigned int mass         = 0;
      static constexpr unsigned int velocity     = 1;
      static constexpr unsigned int force        = 1 + dim;
      static constexpr unsigned int n_components = 1 + 2 * dim;
    };

    static constexpr unsigned int no_slot = numbers::invalid_unsigned_int;

    /**
     * `n_fields` velocity fields per node. Connects to Grid::changed,
     * which calls setup() again.
     */
    explicit GridNodes(const Grid<dim> &grid, const unsigned int n_fields = 1);

    /** Size the storage for the grid's nodes. */
    void
    setup();

    unsigned int
    n_fields() const
    {
      return n_field_count;
    }

    /** The slot of a field at a node, or no_slot where it has none. */
    unsigned int
    slot(const unsigned int node, const unsigned int field) const
    {
      return field == 0 ? node : extra_slot_of[(field - 1) * n_grid_nodes + node];
    }

    /** The node of a slot. */
    unsigned int
    node_of_slot(const unsigned int slot) const
    {
      return slot < n_grid_nodes ? slot : extra_nodes[slot - n_grid_nodes];
    }

    /** The field of a slot. */
    unsigned int
    field_of_slot(const unsigned int slot) const
    {
      return slot < n_grid_nodes ? 0 : extra_fields[slot - n_grid_nodes];
    }

    /**
     * Slots run below this bound (field 0's and the others' made so far),
     * for arrays indexed by slot.
     */
    unsigned int
    n_slots() const
    {
      return n_grid_nodes + extra_nodes.size();
    }

    /**
     * The values of a slot, NodalLayout::n_components of them. A slot of a
     * field other than 0 may move in memory when claim() makes a new one:
     * ask again after claiming.
     */
    double *
    values_of(const unsigned int slot)
    {
      return slot < n_grid_nodes ?
               values.get_values() + slot * NodalLayout::n_components :
               extra_values.data() +
                 (slot - n_grid_nodes) * NodalLayout::n_components;
    }

    const double *
    values_of(const unsigned int slot) const
    {
      return const_cast<GridNodes *>(this)->values_of(slot);
    }

    /**
     * One field seen from a point's support: its slot at a node, the
     * values there, and the slot claimed in a projection. with_field()
     * hands out field 0's view, whose slot is the node itself, apart from
     * the others', so that a loop over a support needs no test per node.
     */
    struct FirstField
    {
      GridNodes &nodes;

      unsigned int
      slot(const unsigned int node) const
      {
        return node;
      }

      double *
      values(const unsigned int node) const
      {
        return nodes.values.get_values() + node * NodalLayout::n_components;
      }

      double *
      claim(const unsigned int node) const
      {
        nodes.claim(node, 0);
        return values(node);
      }
    };

    struct OtherField
    {
      GridNodes &        nodes;
      const unsigned int field;

      unsigned int
      slot(const unsigned int node) const
      {
        return nodes.slot(node, field);
      }

      double *
      values(const unsigned int node) const
      {
        return nodes.values_of(slot(node));
      }

      double *
      claim(const unsigned int node) const
      {
        return nodes.values_of(nodes.claim(node, field));
      }
    };

    /** f(view) with the view of one field (FirstField or OtherField). */
    template <typename Function>
    void
    with_field(const unsigned int field, const Function &f)
    {
      if (field == 0)
        f(FirstField{*this});
      else
        f(OtherField{*this, field});
    }

    template <typename Function>
    void
    with_field(const unsigned int field, const Function &f) const
    {
      const_cast<GridNodes *>(this)->with_field(field, f);
    }

    /** The mass of every field at a node, summed. */
    double
    mass_at(const unsigned int node) const
    {
      double mass = values_of(node)[NodalLayout::mass];
      for (unsigned int field = 1; field < n_field_count; ++field)
        {
          const unsigned int s = slot(node, field);
          if (s != no_slot)
            mass += values_of(s)[NodalLayout::mass];
        }
      return mass;
    }

    /**
     * Start a projection: clear the given range of components on every slot
     * that may hold a value from the last one. Slots then written by a
     * projection of all components must be claimed with claim().
     */
    void
    begin_projection(const unsigned int first_component,
                     const unsigned int n_components);

    /**
     * The slot of a field at a node in a projection of all components: made
     * (with zero values) if the field has none there yet, and marked as
     * written.
     */
    unsigned int
    claim(const unsigned int node, const unsigned int field)
    {
      if (field == 0)
        {
          if (!active_flag[node])
            {
              active_flag[node] = true;
              active_nodes.push_back(node);
            }
          return node;
        }
      unsigned int &s = extra_slot_of[(field - 1) * n_grid_nodes + node];
      if (s == no_slot)
        s = make_slot(node, field);
      return s;
    }

    /**
     * Sum the contributions across ranks, so that every active slot, owned
     * or ghost, holds the full sum. Collective.
     */
    void
    finish_projection();

    /**
     * Slots this rank works on: its active ones and those of its imported
     * nodes, field 0's first.
     */
    const std::vector<unsigned int> &
    slots_to_solve() const
    {
      return solve_slots;
    }

    /**
     * The nodes where more than one field has mass after the last
     * projection: where fields meet. Every rank that has such a node, owned
     * or ghost, lists it.
     */
    std::vector<unsigned int>
    shared_nodes() const;

    /**
     * Combine `width` values per node across the ranks that have the node:
     * `values` holds them for each of `nodes` (local ids, as
     * shared_nodes() gives them) in turn; a ghost node's values go to its
     * owner, which adds them to its own (or takes the largest, if
     * `largest`), and every rank that has the node then holds the owner's
     * result. Each rank must list the same nodes where they are shared.
     * Collective.
     */
    void
    combine_over_ranks(const std::vector<unsigned int> &nodes,
                       std::vector<double> &            values,
                       const unsigned int               width,
                       const bool                       largest) const;

    /**
     * The values as a vector of the FESystem of 1 + 2 dim Q1 components on
     * output_dof_handler(), for the grid output (DataOut): with several
     * fields, their total mass and their centre-of-mass velocity and
     * acceleration. Ghost values are brought up to date first, and the
     * vertices that hang on a coarser cell's face get the values that the
     * nodes of that face give them.
     */
    const LinearAlgebra::distributed::Vector<double> &
    output_vector() const;

    /**
     * The FESystem numbering of the nodes, distributed on the first call
     * after each setup(): only the grid output needs it.
     */
    const DoFHandler<dim> &
    output_dof_handler() const;

  private:
    /** A new slot of a field other than 0 at a node, claimed. */
    unsigned int
    make_slot(const unsigned int node, const unsigned int field);

    /**
     * finish_projection() for the fields other than 0: ghost slots' sums
     * go to their owners, who add them and send the totals back to every
     * rank that has the node as a ghost.
     */
    void
    exchange_extra_fields();

    /** The centre-of-mass values of all fields at a node, into `out`. */
    void
    combine_fields(const unsigned int node, double *out) const;

    const Grid<dim> &  grid;
    const unsigned int n_field_count;
    FESystem<dim>      system_element;
    /**
     * output_dof_handler(): its dof (node, c) is the value c of the node's
     * global index g in the grid's node numbering, n_components g + c
     * (checked when it is built): deal.II numbers a vertex's components
     * together, vertices in the order of the scalar numbering.
     */
    mutable std::unique_ptr<DoFHandler<dim>>           system_dof_handler;
    mutable LinearAlgebra::distributed::Vector<double> values;
    /** With several fields: the combined values for the output. */
    mutable LinearAlgebra::distributed::Vector<double> combined_values;

    unsigned int n_grid_nodes = 0;
    /** Field 0, per node: written by the current projection. */
    std::vector<bool>         active_flag;
    std::vector<unsigned int> active_nodes;
    /** Owned nodes that other ranks may add to in compress(). */
    std::vector<unsigned int> imported_nodes;
    /**
     * The same, once per rank that has them as ghosts, in the order of
     * the partitioner's import targets.
     */
    std::vector<unsigned int> imported_in_order;
    std::vector<unsigned int> solve_slots;
    bool                      full_projection = true;

    /**
     * The other fields: per field f >= 1 and node, the slot, or no_slot
     * (at (f - 1) n_nodes + node); and per slot from n_nodes on its node,
     * field and values.
     */
    std::vector<unsigned int> extra_slot_of;
    std::vector<unsigned int> extra_nodes;
    std::vector<unsigned int> extra_fields;
    std::vector<double>       extra_values;
    /** The rank that owns each ghost node, from n_owned on. */
    std::vector<unsigned int> ghost_owner;

    boost::signals2::scoped_connection grid_changed;
  };
} // namespace mpm

#endif
