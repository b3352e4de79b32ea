#include <talus/io/structure_time_series.h>
#include <talus/structure/line_elements.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

namespace Talus
{
  namespace IO
  {
    namespace
    {
      bool
      is_brake(const Talus::Structure::LineMesh &mesh)
      {
        return dynamic_cast<const Talus::Structure::Brake *>(
                 mesh.element.get()) != nullptr;
      }
    } // namespace


    void
    StructureTimeSeries::open(const std::string                 &filename,
                              const Talus::Structure::Structure &structure,
                              const bool                         root,
                              const std::vector<std::string>    &extra_names)
    {
      n_extra = extra_names.size();
      if (!root)
        return;
      file.open(filename);
      if (!file)
        throw std::runtime_error("cannot write <" + filename + ">");
      file << "time";
      for (const auto &mesh : structure.line_meshes)
        {
          file << ',' << mesh->name << "_force";
          if (is_brake(*mesh))
            file << ',' << mesh->name << "_stroke";
        }
      file << ",dissipated_energy,largest_displacement";
      for (const auto &name : extra_names)
        file << ',' << name;
      file << '\n';
      file << std::setprecision(10);
    }


    void
    StructureTimeSeries::resume(const std::string &filename,
                                const std::string &saved,
                                const bool         root,
                                const std::size_t  n_extra_columns)
    {
      n_extra = n_extra_columns;
      if (!root)
        return;
      std::error_code error;
      std::filesystem::copy_file(
        saved,
        filename,
        std::filesystem::copy_options::overwrite_existing,
        error);
      if (!error)
        file.open(filename, std::ios::app);
      if (error || !file)
        throw std::runtime_error("cannot write <" + filename +
                                 "> (a copy of <" + saved + ">)");
      file << std::setprecision(10);
    }


    void
    StructureTimeSeries::write(const double                       time,
                               const Talus::Structure::Structure &structure,
                               const dealii::Vector<double>      &u,
                               const double               dissipated_energy,
                               const std::vector<double> &extra_values)
    {
      if (!file.is_open())
        return;
      if (extra_values.size() != n_extra)
        throw std::logic_error("StructureTimeSeries: the model's columns "
                               "changed between header and row");
      file << time;
      for (const auto &mesh : structure.line_meshes)
        {
          double force = 0.;
          for (const double N : mesh->force)
            if (std::abs(N) > std::abs(force))
              force = N;
          file << ',' << force;
          if (is_brake(*mesh))
            {
              double stroke = 0.;
              for (const auto &state : mesh->state)
                stroke = std::max(stroke, state.plastic);
              file << ',' << stroke;
            }
        }
      double largest = 0.;
      for (unsigned int k = 0; k < structure.n_nodes(); ++k)
        largest = std::max(largest, structure.node_displacement(u, k).norm());
      file << ',' << dissipated_energy << ',' << largest;
      for (const double v : extra_values)
        file << ',' << v;
      file << '\n';
      file.flush();
    }
  } // namespace IO
} // namespace Talus
