#include <talus/io/point_dump.h>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <utility>
#include <vector>

namespace Talus
{
  namespace IO
  {
    template <int dim>
    void
    write_points_text(const MPM::MaterialPoints<dim> &points,
                      const std::string              &filename,
                      const MPI_Comm                  communicator)
    {
      using Line =
        std::pair<dealii::types::particle_index, std::vector<double>>;
      std::vector<Line> local;
      for (const auto &p : points.particle_handler())
        {
          std::vector<double> values;
          for (unsigned int d = 0; d < dim; ++d)
            values.push_back(p.get_location()[d]);
          const auto props = p.get_properties();
          values.insert(values.end(), props.begin(), props.end());
          local.emplace_back(p.get_id(), values);
        }
      const auto all = dealii::Utilities::MPI::gather(communicator, local);
      if (dealii::Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      std::vector<Line> sorted;
      for (const auto &part : all)
        sorted.insert(sorted.end(), part.begin(), part.end());
      std::sort(sorted.begin(), sorted.end());
      std::ofstream out(filename);
      out << std::setprecision(17);
      for (const auto &[id, values] : sorted)
        {
          out << id;
          for (const double v : values)
            out << ' ' << v;
          out << '\n';
        }
    }


    template void
    write_points_text<2>(const MPM::MaterialPoints<2> &,
                         const std::string &,
                         const MPI_Comm);
    template void
    write_points_text<3>(const MPM::MaterialPoints<3> &,
                         const std::string &,
                         const MPI_Comm);
  } // namespace IO
} // namespace Talus
