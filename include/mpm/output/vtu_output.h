#ifndef mpm_output_vtu_output_h
#define mpm_output_vtu_output_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/fe/mapping.h>

#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <mpm/assembly/grid_nodes.h>
#include <mpm/basis/node_cloud.h>
#include <mpm/points/material_points.h>

#include <string>
#include <utility>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * ParaView output: the material points with all their properties, and
   * optionally the grid with its nodal mass, velocity and acceleration, as
   * VTU files per rank, a PVTU per snapshot and a PVD series per kind
   * (points.pvd, grid.pvd) that is rewritten after every snapshot, so a run
   * that stops early leaves a readable series.
   */
  template <int dim>
  class VtuOutput
  {
  public:
    /** `Write ParaView output`, `Interval` and `Write grid`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Parse the `Output` subsection (the handler is at top level); files go
     * into `directory`. An Interval that would write more than 100,000
     * snapshots before `end_time` is refused (InputError).
     */
    VtuOutput(ParameterHandler & prm,
              const std::string &directory,
              const double       end_time,
              const MPI_Comm     communicator);

    /** Whether snapshots are written at all. */
    bool
    enabled() const
    {
      return write_paraview;
    }

    /** Simulated time between snapshots; 0: the first and the last only. */
    double
    interval() const
    {
      return snapshot_interval;
    }

    void
    write(const double               time,
          const MaterialPoints<dim> &points,
          const GridNodes<dim> &     nodes,
          const Mapping<dim> &       mapping,
          const NodeCloud<dim> *     cloud = nullptr);

    /**
     * The file counter and the .pvd records, for Checkpoint. Loading
     * rewrites the .pvd files, which then leave out any snapshot written
     * after the checkpoint.
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &counter &point_records &grid_records &cloud_records;
      if (Archive::is_loading::value)
        {
          write_series("points", point_records);
          write_series("grid", grid_records);
          write_series("nodes", cloud_records);
        }
    }

  private:
    /**
     * Write one snapshot (VTU per rank, PVTU) and rewrite its PVD series.
     * Points are patches of dimension 0, grid cells of dimension dim.
     */
    template <int patch_dim>
    void
    write_snapshot(const DataOutInterface<patch_dim, dim> &      data_out,
                   const std::string &                           name,
                   const double                                  time,
                   std::vector<std::pair<double, std::string>> &records) const;

    /** Rank 0 writes the series `name`.pvd of the records, if any. */
    void
    write_series(
      const std::string &                                name,
      const std::vector<std::pair<double, std::string>> &records) const;

    const std::string directory;
    bool              write_paraview;
    double            snapshot_interval;
    bool              write_grid;
    const MPI_Comm    communicator;
    unsigned int      counter = 0;

    std::vector<std::pair<double, std::string>> point_records;
    std::vector<std::pair<double, std::string>> grid_records;
    std::vector<std::pair<double, std::string>> cloud_records;
  };
} // namespace mpm

#endif
