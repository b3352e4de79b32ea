// Structure verification model: a continuum solid alone (model solid).

#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/solid_model.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

namespace Talus
{
  namespace StructureModels
  {
    using namespace dealii;

    // ------------------------------------------------------------------
    /**
     * Mean of displacement component @p c of solid mesh @p mesh over its
     * faces with boundary id @p id, int u_c dA0 / A0 (the work-conjugate
     * of a uniform traction along c) [m].
     */
    /** The DoF values of @p mesh out of the structure's vector @p u. */
    template <int dim>
    Vector<double>
    mesh_dofs(const Talus::Structure::SolidMeshT<dim> &mesh,
              const Vector<double>                    &u)
    {
      Vector<double> local(mesh.dof_handler.n_dofs());
      for (unsigned int i = 0; i < local.size(); ++i)
        local[i] = u[mesh.offset + i];
      return local;
    }


    template <int dim>
    double
    face_mean(const Talus::Structure::SolidMeshT<dim> &mesh,
              const Vector<double>                    &u,
              const unsigned int                       id,
              const unsigned int                       c)
    {
      const QGauss<dim - 1>            quadrature(mesh.fe->degree + 1);
      FEFaceValues<dim, 3>             fe_face_values(*mesh.fe,
                                          quadrature,
                                          update_values | update_JxW_values);
      const FEValuesExtractors::Scalar uc(c);
      const Vector<double>             local = mesh_dofs(mesh, u);
      std::vector<double>              values(quadrature.size());
      double                           integral = 0., area = 0.;
      for (const auto &cell : mesh.dof_handler.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->at_boundary(f) && cell->face(f)->boundary_id() == id)
            {
              fe_face_values.reinit(cell, f);
              fe_face_values[uc].get_function_values(local, values);
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                {
                  integral += values[q] * fe_face_values.JxW(q);
                  area += fe_face_values.JxW(q);
                }
            }
      return integral / area;
    }


    template double
    face_mean(const Talus::Structure::SolidMeshT<2> &,
              const Vector<double> &,
              const unsigned int,
              const unsigned int);
    template double
    face_mean(const Talus::Structure::SolidMeshT<3> &,
              const Vector<double> &,
              const unsigned int,
              const unsigned int);


    template <int dim>
    double
    region_mean(const Talus::Structure::SolidMeshT<dim> &mesh,
                const Vector<double>                    &u,
                const double                             x_min,
                const unsigned int                       c)
    {
      const QGauss<dim>                quadrature(mesh.fe->degree + 1);
      FEValues<dim, 3>                 fe_values(*mesh.fe,
                                 quadrature,
                                 update_values | update_JxW_values);
      const FEValuesExtractors::Scalar uc(c);
      const Vector<double>             local = mesh_dofs(mesh, u);
      std::vector<double>              values(quadrature.size());
      double                           integral = 0., volume = 0.;
      for (const auto &cell : mesh.dof_handler.active_cell_iterators())
        if (cell->center()[0] > x_min)
          {
            fe_values.reinit(cell);
            fe_values[uc].get_function_values(local, values);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                integral += values[q] * fe_values.JxW(q);
                volume += fe_values.JxW(q);
              }
          }
      return volume > 0. ? integral / volume : 0.;
    }


    template double
    region_mean(const Talus::Structure::SolidMeshT<2> &,
                const Vector<double> &,
                const double,
                const unsigned int);
    template double
    region_mean(const Talus::Structure::SolidMeshT<3> &,
                const Vector<double> &,
                const double,
                const unsigned int);


    std::unique_ptr<Model>
    create_solid_model(const Parameters &p)
    {
      return std::make_unique<SolidModel>(p);
    }
  } // namespace StructureModels
} // namespace Talus
