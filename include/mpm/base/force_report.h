#ifndef mpm_base_force_report_h
#define mpm_base_force_report_h

#include <string>
#include <vector>

namespace mpm
{
  /**
   * Whatever reports forces in the time series: the walls and obstacles
   * (NodalCondition) and the contact between bodies (FieldContact). Each
   * names its columns once and gives their values at each row.
   */
  class ForceReport
  {
  public:
    virtual ~ForceReport() = default;

    /** Names of the forces reported in the time series. */
    virtual std::vector<std::string>
    force_names() const
    {
      return {};
    }

    /** Those forces at the last nodal solve, on every rank. Collective. */
    virtual std::vector<double>
    forces() const
    {
      return {};
    }

    /**
     * At an output time: write the forces node by node into `directory`,
     * named with the step. Collective.
     */
    virtual void
    write_tractions(const std::string &, const unsigned int) const
    {}
  };
} // namespace mpm

#endif
