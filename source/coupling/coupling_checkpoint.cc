// Checkpoints of the coupled problem (doc/checkpoint.md): the state the
// coupling carries from step to step (accelerators, predictor, convergence
// criterion) and GaussSeidelCoupling::save_checkpoint() and
// load_checkpoint(), which add the structure's and the coupling's archives
// to the MPM's checkpoint files.

#include <talus/base/input.h>
#include <talus/coupling/accelerators.h>
#include <talus/coupling/convergence_criterion.h>
#include <talus/coupling/gauss_seidel_coupling.h>
#include <talus/coupling/iqn_imvj.h>
#include <talus/coupling/predictor.h>
#include <talus/io/checkpointing.h>

#include <deal.II/base/mpi.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <string>
#include <vector>

namespace Talus
{
  namespace Coupling
  {
    namespace
    {
      /** Write a deque of columns: their number, then each with @p item. */
      template <class Deque, class Item>
      void
      save_columns(boost::archive::binary_oarchive &archive,
                   const Deque                     &columns,
                   const Item                      &item)
      {
        const std::size_t n = columns.size();
        archive << n;
        for (const auto &column : columns)
          item(column);
      }

      template <class Deque, class Item>
      void
      load_columns(boost::archive::binary_iarchive &archive,
                   Deque                           &columns,
                   const Item                      &item)
      {
        std::size_t n = 0;
        archive >> n;
        columns.clear();
        columns.resize(n);
        for (auto &column : columns)
          item(column);
      }

      template <class Archive>
      void
      serialize_info(Archive &archive, AccelerationInfo &info)
      {
        archive &info.relaxation;
        archive &info.quasi_newton;
        archive &info.columns;
        archive &info.filtered_columns;
        archive &info.fallback;
      }

      const std::string structure_tag = "talus-structure-state";
      const std::string coupling_tag  = "talus-coupling-state";
    } // namespace


    void
    InterfaceAccelerator::save(boost::archive::binary_oarchive &archive) const
    {
      AccelerationInfo info = last_info;
      serialize_info(archive, info);
      archive << window_iteration;
    }


    void
    InterfaceAccelerator::load(boost::archive::binary_iarchive &archive)
    {
      serialize_info(archive, last_info);
      archive >> window_iteration;
    }


    void
    AitkenRelaxation::save(boost::archive::binary_oarchive &archive) const
    {
      InterfaceAccelerator::save(archive);
      archive << omega << previous_residual << have_previous;
    }


    void
    AitkenRelaxation::load(boost::archive::binary_iarchive &archive)
    {
      InterfaceAccelerator::load(archive);
      archive >> omega >> previous_residual >> have_previous;
    }


    void
    IQNILS::save(boost::archive::binary_oarchive &archive) const
    {
      InterfaceAccelerator::save(archive);
      save_columns(archive, columns, [&](const Column &c) {
        archive << c.delta_residual << c.delta_x_tilde << c.window;
      });
      archive << previous_residual << previous_x_tilde << have_previous
              << stagnated << window << window_converged << filtered_total;
    }


    void
    IQNILS::load(boost::archive::binary_iarchive &archive)
    {
      InterfaceAccelerator::load(archive);
      load_columns(archive, columns, [&](Column &c) {
        archive >> c.delta_residual >> c.delta_x_tilde >> c.window;
      });
      archive >> previous_residual >> previous_x_tilde >> have_previous >>
        stagnated >> window >> window_converged >> filtered_total;
    }


    void
    IQNIMVJ::save(boost::archive::binary_oarchive &archive) const
    {
      InterfaceAccelerator::save(archive);
      save_columns(archive, columns, [&](const Column &c) {
        archive << c.delta_residual << c.delta_x_tilde;
      });
      // J_prev row by row (n x n, replicated)
      const std::size_t   m = jacobian.m(), n = jacobian.n();
      std::vector<double> entries;
      entries.reserve(m * n);
      for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = 0; j < n; ++j)
          entries.push_back(jacobian(i, j));
      archive << m << n << entries << have_jacobian << previous_residual
              << previous_x_tilde << have_previous << stagnated
              << filtered_total;
    }


    void
    IQNIMVJ::load(boost::archive::binary_iarchive &archive)
    {
      InterfaceAccelerator::load(archive);
      load_columns(archive, columns, [&](Column &c) {
        archive >> c.delta_residual >> c.delta_x_tilde;
      });
      std::size_t         m = 0, n = 0;
      std::vector<double> entries;
      archive >> m >> n >> entries;
      if (entries.size() != m * n)
        throw boost::archive::archive_exception(
          boost::archive::archive_exception::input_stream_error);
      jacobian.reinit(m, n);
      for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = 0; j < n; ++j)
          jacobian(i, j) = entries[i * n + j];
      archive >> have_jacobian >> previous_residual >> previous_x_tilde >>
        have_previous >> stagnated >> filtered_total;
    }


    void
    InterfacePredictor::save(boost::archive::binary_oarchive &archive) const
    {
      const std::vector<double> t(times.begin(), times.end());
      archive << t;
      save_columns(archive, values, [&](const dealii::Vector<double> &v) {
        archive << v;
      });
    }


    void
    InterfacePredictor::load(boost::archive::binary_iarchive &archive)
    {
      std::vector<double> t;
      archive >> t;
      times.assign(t.begin(), t.end());
      load_columns(archive, values, [&](dealii::Vector<double> &v) {
        archive >> v;
      });
      if (values.size() != times.size())
        throw boost::archive::archive_exception(
          boost::archive::archive_exception::input_stream_error);
    }


    template <int dim>
    void
    GaussSeidelCoupling<dim>::save_checkpoint(const std::string &directory,
                                              const std::string &model) const
    {
      mpm.save_checkpoint(directory);
      if (dealii::Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      const auto &S = structure.get_structure();
      IO::Checkpointing::save_archive(directory + "/structure_state",
                                      structure_tag,
                                      [&](auto &archive) {
                                        std::string        name   = model;
                                        unsigned long long n_dofs = S.n_dofs();
                                        bool dynamic = structure.is_dynamic();
                                        std::vector<std::string>        names;
                                        std::vector<unsigned long long> sizes;
                                        for (const auto &mesh : S.line_meshes)
                                          {
                                            names.push_back(mesh->name);
                                            sizes.push_back(mesh->state.size());
                                          }
                                        archive << name << n_dofs << dynamic
                                                << names << sizes;
                                        structure.save_committed_state(archive);
                                      });
      IO::Checkpointing::save_archive(
        directory + "/coupling_state", coupling_tag, [&](auto &archive) {
          std::string        name     = acceleration->name();
          unsigned long long n_values = committed.size();
          archive << name << n_values << committed << force << committed_force
                  << step_end;
          predictor.save(archive);
          auto &c = const_cast<ConvergenceCriterion &>(criterion);
          c.serialize_state(archive);
          acceleration->save(archive);
        });
    }


    template <int dim>
    void
    GaussSeidelCoupling<dim>::load_checkpoint(const std::string &directory,
                                              const std::string &model)
    {
      const std::string structure_file = directory + "/structure_state";
      const std::string coupling_file  = directory + "/coupling_state";
      const auto        where          = [&](const std::string &file) {
        return "Cannot resume from the checkpoint <" + directory +
               ">: the file <" + file + "> does not fit the parameter file: ";
      };
      // The structure first: a mismatch is found before the MPM's grid is
      // loaded.
      auto &S = structure.get_structure();
      IO::Checkpointing::load_archive(
        directory, structure_file, structure_tag, [&](auto &archive) {
          std::string                     name;
          unsigned long long              n_dofs  = 0;
          bool                            dynamic = false;
          std::vector<std::string>        names;
          std::vector<unsigned long long> sizes;
          archive >> name >> n_dofs >> dynamic >> names >> sizes;
          if (name != model)
            throw ExcInvalidInput(where(structure_file) +
                                  "it holds the state of the structure "
                                  "model '" +
                                  name + "', the parameter file sets '" +
                                  model + "' (subsection <Structure>).");
          if (n_dofs != S.n_dofs())
            throw ExcInvalidInput(
              where(structure_file) + "it holds a structure of " +
              std::to_string(n_dofs) + " DoFs, the parameter file's has " +
              std::to_string(S.n_dofs()) +
              " (subsection <Structure>: the mesh, e.g. 'elements per "
              "member').");
          if (dynamic != structure.is_dynamic())
            throw ExcInvalidInput(
              where(structure_file) + "it holds a " +
              (dynamic ? "dynamic" : "static") +
              " structure, the parameter file's is " +
              (structure.is_dynamic() ? "dynamic" : "static") +
              " (subsection <Structure/Dynamics>, 'dynamic').");
          bool same = names.size() == S.line_meshes.size();
          for (unsigned int m = 0; same && m < names.size(); ++m)
            same = names[m] == S.line_meshes[m]->name &&
                   sizes[m] == S.line_meshes[m]->state.size();
          if (!same)
            throw ExcInvalidInput(where(structure_file) +
                                  "its line meshes (members and their "
                                  "elements) differ from those of the "
                                  "parameter file's structure (subsection "
                                  "<Structure>).");
          structure.load_committed_state(archive, where(structure_file));
        });
      IO::Checkpointing::load_archive(
        directory, coupling_file, coupling_tag, [&](auto &archive) {
          std::string        name;
          unsigned long long n_values = 0;
          archive >> name >> n_values;
          if (name != acceleration->name())
            throw ExcInvalidInput(where(coupling_file) +
                                  "it holds the history of the accelerator "
                                  "'" +
                                  name + "', the parameter file sets '" +
                                  acceleration->name() +
                                  "' (subsection <Coupling>, "
                                  "'acceleration').");
          if (n_values != S.n_dofs())
            throw ExcInvalidInput(
              where(coupling_file) + "its interface vectors have " +
              std::to_string(n_values) + " values, the structure has " +
              std::to_string(S.n_dofs()) + " DoFs.");
          archive >> committed >> force >> committed_force >> step_end;
          predictor.load(archive);
          criterion.serialize_state(archive);
          acceleration->load(archive);
        });

      // The MPM (its own identity checks), then the interface for the
      // boundary particles loaded (their ids are those of the run that
      // wrote the checkpoint) at the committed displacement.
      mpm.load_checkpoint(directory);
      interface.setup(mpm.boundaries(), communicator);
      interface.set_step_displacement(committed, committed, step_end, step_end);
    }


    template void
    GaussSeidelCoupling<2>::save_checkpoint(const std::string &,
                                            const std::string &) const;
    template void
    GaussSeidelCoupling<3>::save_checkpoint(const std::string &,
                                            const std::string &) const;
    template void
    GaussSeidelCoupling<2>::load_checkpoint(const std::string &,
                                            const std::string &);
    template void
    GaussSeidelCoupling<3>::load_checkpoint(const std::string &,
                                            const std::string &);
  } // namespace Coupling
} // namespace Talus
