// The structure's assembly: residual and tangent of all elements (lines,
// sliding cables, membranes, solids), the consistent mass, energies and
// the potential of the loads. Setup, meshes and DoFs: structure.cc.

#include <talus/structure/structure.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <algorithm>

namespace Talus
{
  namespace Structure
  {
    using dealii::types::global_dof_index;


    namespace
    {
      /** rho int N_i N_j dV of one cell (same components only) into
       * @p Me, for @p fe_values reinitialised on it. */
      template <int dim>
      void
      cell_mass_matrix(const dealii::FEValues<dim, 3> &fe_values,
                       const double                    rho,
                       dealii::FullMatrix<double>     &Me)
      {
        const auto        &fe = fe_values.get_fe();
        const unsigned int n  = fe.n_dofs_per_cell();
        Me.reinit(n, n);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            {
              const unsigned int ci = fe.system_to_component_index(i).first;
              if (ci != fe.system_to_component_index(j).first)
                continue;
              for (const unsigned int q : fe_values.quadrature_point_indices())
                Me(i, j) += rho * fe_values.shape_value_component(i, q, ci) *
                            fe_values.shape_value_component(j, q, ci) *
                            fe_values.JxW(q);
            }
      }
    } // namespace


    void
    Structure::assemble_consistent_mass(dealii::SparseMatrix<double> &M) const
    {
      M.reinit(sparsity);
      std::vector<global_dof_index> indices;
      dealii::FullMatrix<double>    Me;
      for (const auto &mesh : line_meshes)
        {
          if (mesh->sliding_cable)
            {
              // Lumped: the nodes slide along the cable.
              const double rhoA =
                mesh->sliding_cable->density * mesh->sliding_cable->area;
              indices.resize(6);
              Me.reinit(6, 6);
              for (unsigned int k = 0; k + 1 < mesh->chain.size(); ++k)
                {
                  const double m =
                    0.5 * rhoA *
                    (mesh->chain_X[k + 1] - mesh->chain_X[k]).norm();
                  for (unsigned int c = 0; c < 3; ++c)
                    {
                      indices[c]       = mesh->chain[k][c];
                      indices[3 + c]   = mesh->chain[k + 1][c];
                      Me(c, c)         = m;
                      Me(3 + c, 3 + c) = m;
                    }
                  constraints.distribute_local_to_global(Me, indices, M);
                }
              continue;
            }
          indices.resize(6);
          Me.reinit(6, 6);
          for (const auto &cell : mesh->dof_handler.active_cell_iterators())
            {
              const double m = mesh->element->mass_per_length() *
                               cell->vertex(0).distance(cell->vertex(1));
              Me = 0.;
              for (unsigned int v = 0; v < 2; ++v)
                for (unsigned int w = 0; w < 2; ++w)
                  for (unsigned int c = 0; c < 3; ++c)
                    Me(3 * v + c, 3 * w + c) = m / 6. * (v == w ? 2. : 1.);
              for (unsigned int v = 0; v < 2; ++v)
                for (unsigned int c = 0; c < 3; ++c)
                  indices[3 * v + c] =
                    mesh->offset + cell->vertex_dof_index(v, c);
              constraints.distribute_local_to_global(Me, indices, M);
            }
        }
      // rho int N_i N_j dV over the cells of one continuum mesh
      const auto add_cells = [&](const auto            &dof_handler,
                                 const global_dof_index offset,
                                 auto                  &fe_values,
                                 const double           rho) {
        const unsigned int n = fe_values.get_fe().n_dofs_per_cell();
        indices.resize(n);
        Me.reinit(n, n);
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            fe_values.reinit(cell);
            cell->get_dof_indices(indices);
            for (auto &i : indices)
              i += offset;
            cell_mass_matrix(fe_values, rho, Me);
            constraints.distribute_local_to_global(Me, indices, M);
          }
      };
      if (!membrane_meshes.empty())
        {
          const dealii::QGauss<2> quadrature(2);
          dealii::FEValues<2, 3>  fe_values(membrane_fe,
                                           quadrature,
                                           dealii::update_values |
                                             dealii::update_JxW_values);
          for (const auto &mesh : membrane_meshes)
            add_cells(mesh->dof_handler,
                      mesh->offset,
                      fe_values,
                      mesh->membrane->density *
                        mesh->membrane->material.thickness);
        }
      for_each_solid_mesh([&](auto &solid_mesh) {
        constexpr int dim = std::decay_t<decltype(solid_mesh)>::dimension;
        const auto   &fe  = *solid_mesh.fe;
        const dealii::QGauss<dim> quadrature(fe.degree + 1);
        dealii::FEValues<dim, 3>  fe_values(
          fe, quadrature, dealii::update_values | dealii::update_JxW_values);
        add_cells(solid_mesh.dof_handler,
                  solid_mesh.offset,
                  fe_values,
                  solid_mesh.solid->density * solid_mesh.thickness);
      });
    }


    double
    Structure::load_potential(const dealii::Vector<double> &u,
                              const double                  load_factor) const
    {
      double V = 0.;
      for (global_dof_index i = 0; i < total_dofs; ++i)
        V -= external_forces[i] * u[i];
      for (global_dof_index i = 0; i < total_dofs; ++i)
        V -= (scale_gravity ? load_factor : 1.) * mass[i] *
               gravity[dof_component[i]] * u[i] +
             load_factor * traction_forces[i] * u[i];
      for (const auto &[node, F] : point_loads)
        for (unsigned int c = 0; c < 3; ++c)
          V -= load_factor * F[c] * u[nodes[node].dofs[c]];
      return V;
    }


    void
    Structure::apply_prescribed(dealii::Vector<double> &u,
                                const double            load_factor) const
    {
      for (const auto &p : prescribed)
        u[p.first] = load_factor * p.second;
      ties.distribute(u);
    }


    double
    Structure::assemble(const dealii::Vector<double> &u,
                        const double                  load_factor,
                        dealii::Vector<double>       &r,
                        dealii::SparseMatrix<double> *K)
    {
      r.reinit(total_dofs);
      raw_residual       = 0.;
      last_strain_energy = 0.;
      if (K != nullptr)
        *K = 0.;
      const auto add = [&](const dealii::FullMatrix<double>    &Ke,
                           const dealii::Vector<double>        &re,
                           const std::vector<global_dof_index> &indices) {
        for (unsigned int i = 0; i < indices.size(); ++i)
          raw_residual[indices[i]] += re[i];
        if (K != nullptr)
          constraints.distribute_local_to_global(Ke, re, indices, *K, r);
        else
          constraints.distribute_local_to_global(re, indices, r);
      };
      const dealii::Tensor<1, 3> g =
        (scale_gravity ? load_factor : 1.) * gravity;

      // Line meshes.
      std::vector<global_dof_index> indices(6);
      LineResponse                  response;
      for (auto &mesh : line_meshes)
        {
          if (mesh->sliding_cable)
            {
              const unsigned int                n = mesh->chain.size();
              std::vector<dealii::Tensor<1, 3>> x(n);
              indices.clear();
              for (unsigned int k = 0; k < n; ++k)
                {
                  for (unsigned int c = 0; c < 3; ++c)
                    {
                      x[k][c] = mesh->chain_X[k][c] + u[mesh->chain[k][c]];
                      indices.push_back(mesh->chain[k][c]);
                    }
                }
              dealii::Vector<double>     f;
              dealii::FullMatrix<double> Ke;
              double                     N     = 0.;
              const auto                &cable = *mesh->sliding_cable;
              if (cable.stick_slip && cable.friction_coefficient > 0.)
                {
                  // History: material length of each segment, stored as
                  // its change from the reference length (LineState::plastic).
                  std::vector<double> old_lengths(n - 1), new_lengths;
                  for (unsigned int k = 0; k + 1 < n; ++k)
                    old_lengths[k] =
                      (mesh->chain_X[k + 1] - mesh->chain_X[k]).norm() +
                      mesh->state[mesh->chain_cells[k]].plastic;
                  N = cable.compute(
                    mesh->chain_X, x, old_lengths, f, Ke, new_lengths);
                  for (unsigned int k = 0; k + 1 < n; ++k)
                    mesh->trial_state[mesh->chain_cells[k]].plastic =
                      new_lengths[k] -
                      (mesh->chain_X[k + 1] - mesh->chain_X[k]).norm();
                }
              else
                {
                  double energy = 0.;
                  N = cable.compute(mesh->chain_X, x, f, Ke, &energy);
                  last_strain_energy += energy;
                }
              const double rhoA =
                mesh->sliding_cable->density * mesh->sliding_cable->area;
              for (unsigned int k = 0; k + 1 < n; ++k)
                {
                  const double L =
                    (mesh->chain_X[k + 1] - mesh->chain_X[k]).norm();
                  for (unsigned int c = 0; c < 3; ++c)
                    {
                      f[3 * k + c] -= 0.5 * rhoA * L * g[c];
                      f[3 * (k + 1) + c] -= 0.5 * rhoA * L * g[c];
                    }
                }
              std::fill(mesh->force.begin(), mesh->force.end(), N);
              if (mesh->sliding_cable->friction_coefficient > 0.)
                for (unsigned int k = 0; k < mesh->chain_cells.size(); ++k)
                  mesh->force[mesh->chain_cells[k]] =
                    mesh->sliding_cable->segment_forces[k];
              add(Ke, f, indices);
              indices.resize(6);
              continue;
            }
          for (const auto &cell : mesh->dof_handler.active_cell_iterators())
            {
              dealii::Tensor<1, 3> X[2], x[2];
              for (unsigned int v = 0; v < 2; ++v)
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    indices[3 * v + c] =
                      mesh->offset + cell->vertex_dof_index(v, c);
                    X[v][c] = cell->vertex(v)[c];
                    x[v][c] = X[v][c] + u[indices[3 * v + c]];
                  }
              const unsigned int k = cell->active_cell_index();
              mesh->element->compute(
                X[0], X[1], x[0], x[1], mesh->state[k], response);
              mesh->trial_state[k] = response.state;
              mesh->force[k]       = response.force;
              last_strain_energy += response.energy;
              const double m =
                mesh->element->mass_per_length() * (X[1] - X[0]).norm();
              for (unsigned int v = 0; v < 2; ++v)
                for (unsigned int c = 0; c < 3; ++c)
                  response.f[3 * v + c] -= 0.5 * m * g[c];
              add(response.K, response.f, indices);
            }
        }

      // Membranes.
      if (!membrane_meshes.empty())
        {
          const dealii::QGauss<2>       quadrature(2);
          dealii::FEValues<2, 3>        fe_values(membrane_fe,
                                           quadrature,
                                           dealii::update_values |
                                             dealii::update_gradients |
                                             dealii::update_jacobians |
                                             dealii::update_JxW_values);
          const unsigned int            n = membrane_fe.n_dofs_per_cell();
          std::vector<global_dof_index> mindices(n);
          std::vector<double>           ue(n);
          dealii::Vector<double>        re;
          dealii::FullMatrix<double>    Ke;
          for (auto &mesh : membrane_meshes)
            {
              const Membrane &membrane = *mesh->membrane;
              const double    rho_t =
                membrane.density * membrane.material.thickness;
              for (const auto &cell : mesh->dof_handler.active_cell_iterators())
                {
                  fe_values.reinit(cell);
                  cell->get_dof_indices(mindices);
                  for (unsigned int i = 0; i < n; ++i)
                    {
                      mindices[i] += mesh->offset;
                      ue[i] = u[mindices[i]];
                    }
                  membrane.compute(
                    fe_values,
                    ue,
                    load_factor,
                    re,
                    Ke,
                    &mesh->cell_output[cell->active_cell_index()]);
                  last_strain_energy +=
                    mesh->cell_output[cell->active_cell_index()].strain_energy;
                  if (rho_t != 0.)
                    for (unsigned int q = 0; q < quadrature.size(); ++q)
                      for (unsigned int i = 0; i < n; ++i)
                        {
                          const unsigned int c =
                            membrane_fe.system_to_component_index(i).first;
                          re[i] -= rho_t * g[c] *
                                   fe_values.shape_value_component(i, q, c) *
                                   fe_values.JxW(q);
                        }
                  add(Ke, re, mindices);
                }
            }
        }

      // Solids: internal forces, gravity and tractions.
      for_each_solid_mesh([&](auto &solid_mesh) {
        auto *const   mesh = &solid_mesh;
        constexpr int dim  = std::decay_t<decltype(solid_mesh)>::dimension;

        const auto               &fe = *mesh->fe;
        const dealii::QGauss<dim> quadrature(fe.degree + 1);
        dealii::FEValues<dim, 3>  fe_values(fe,
                                           quadrature,
                                           dealii::update_values |
                                             dealii::update_gradients |
                                             dealii::update_JxW_values);
        const unsigned int        n   = fe.n_dofs_per_cell();
        const double              rho = mesh->solid->density * mesh->thickness;
        std::vector<global_dof_index> sindices(n);
        std::vector<double>           ue(n);
        dealii::Vector<double>        re;
        dealii::FullMatrix<double>    Ke;
        for (const auto &cell : mesh->dof_handler.active_cell_iterators())
          {
            fe_values.reinit(cell);
            cell->get_dof_indices(sindices);
            for (unsigned int i = 0; i < n; ++i)
              {
                sindices[i] += mesh->offset;
                ue[i] = u[sindices[i]];
              }
            auto &output = mesh->cell_output[cell->active_cell_index()];
            mesh->solid->compute(fe_values, ue, re, Ke, &output);
            if (mesh->thickness != 1.)
              {
                // Plane strain: per unit thickness times t.
                re *= mesh->thickness;
                Ke *= mesh->thickness;
                output.strain_energy *= mesh->thickness;
              }
            last_strain_energy += output.strain_energy;
            for (unsigned int i = 0; i < n; ++i)
              {
                const unsigned int c = fe.system_to_component_index(i).first;
                if (rho != 0. && g[c] != 0.)
                  for (const unsigned int q :
                       fe_values.quadrature_point_indices())
                    re[i] -= rho * g[c] *
                             fe_values.shape_value_component(i, q, c) *
                             fe_values.JxW(q);
              }
            add(Ke, re, sindices);
          }
      });

      // Point loads and external forces.
      {
        std::vector<global_dof_index> one(1);
        dealii::Vector<double>        value(1);
        for (const auto &[node, F] : point_loads)
          for (unsigned int c = 0; c < 3; ++c)
            {
              one[0]   = nodes[node].dofs[c];
              value[0] = -load_factor * F[c];
              raw_residual[one[0]] += value[0];
              constraints.distribute_local_to_global(value, one, r);
            }
        for (global_dof_index i = 0; i < total_dofs; ++i)
          if (traction_forces[i] != 0.)
            {
              one[0]   = i;
              value[0] = -load_factor * traction_forces[i];
              raw_residual[i] += value[0];
              constraints.distribute_local_to_global(value, one, r);
            }
        for (global_dof_index i = 0; i < total_dofs; ++i)
          if (external_forces[i] != 0.)
            {
              one[0]   = i;
              value[0] = -external_forces[i];
              raw_residual[i] += value[0];
              constraints.distribute_local_to_global(value, one, r);
            }
        if (interface_springs.size() == total_dofs)
          {
            dealii::FullMatrix<double> k(1, 1);
            for (global_dof_index i = 0; i < total_dofs; ++i)
              if (interface_springs[i] != 0.)
                {
                  one[0]   = i;
                  k(0, 0)  = interface_springs[i];
                  value[0] = k(0, 0) * (u[i] - interface_anchor[i]);
                  raw_residual[i] += value[0];
                  if (K != nullptr)
                    constraints.distribute_local_to_global(
                      k, value, one, *K, r);
                  else
                    constraints.distribute_local_to_global(value, one, r);
                }
          }
      }
      return r.l2_norm();
    }
  } // namespace Structure
} // namespace Talus
