// Linear Dirichlet-Neumann model problems of the coupling tests
// (../shared/VERIFICATION.md §4, NOTES-structures-coupling.md §0.4).
//
// Dirichlet side (the MPM): a soil mass m on a soil spring k_s, integrated
// with Newmark (beta = 1/4). Given the interface displacement d at t_{n+1}
// the soil's acceleration is a = (d - d_n - dt v_n - dt^2 (1/2 - beta) a_n)
// / (beta dt^2), and the force it exerts on the barrier is
// f = -(m a + k_s d) = f_0 - k_D d with the effective interface stiffness
// k_D = k_s + m/(beta dt^2) (inertia included).
// Neumann side (the barrier): a spring k_N, d~ = f/k_N.
// Fixed point H(d) = (f_0 - k_D d)/k_N, amplification dH/dd = -k_D/k_N,
// solution d* = f_0/(k_N + k_D), optimal constant relaxation
// omega* = k_N/(k_N + k_D).
//
// The vector model replaces k_D by a diagonal matrix (the soil at each
// interface node) and k_N by a tridiagonal string stiffness.

#ifndef talus_tests_coupling_two_spring_model_h
#define talus_tests_coupling_two_spring_model_h

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cmath>
#include <vector>

namespace TwoSpring
{
  using dealii::FullMatrix;
  using dealii::Vector;

  /** Scalar model with k_D/k_N = ratio, k_N = 1e6 N/m, dt = 1e-3 s. */
  struct Scalar
  {
    double k_N  = 1e6;  // barrier stiffness [N/m]
    double dt   = 1e-3; // time step [s]
    double beta = 0.25; // Newmark
    double k_s;         // soil spring [N/m]
    double m;           // soil mass [kg]
    double k_D;         // effective Dirichlet stiffness [N/m]
    double f_0;         // force at d = 0 [N]

    // Soil at rest at d_n = 0, arriving with v_n = 5 m/s, a_n = 0; 20 % of
    // k_D from the spring, 80 % from the inertia.
    explicit Scalar(const double ratio, const double v_n = 5.)
    {
      k_D              = ratio * k_N;
      k_s              = 0.2 * k_D;
      m                = 0.8 * k_D * beta * dt * dt;
      const double d_n = 0., a_n = 0.;
      f_0 =
        m * (d_n + dt * v_n + dt * dt * (0.5 - beta) * a_n) / (beta * dt * dt);
    }

    double
    force(const double d) const
    {
      return f_0 - k_D * d;
    }

    void
    operator()(const Vector<double> &x, Vector<double> &x_tilde) const
    {
      x_tilde.reinit(1);
      x_tilde[0] = force(x[0]) / k_N;
    }

    double
    solution() const
    {
      return f_0 / (k_N + k_D);
    }

    double
    optimal_relaxation() const
    {
      return k_N / (k_N + k_D);
    }
  };


  /**
   * Vector model: K_D = diag(k_D,i) (inertia + soil spring at each
   * interface node), K_N = k_N tridiag(-1, 2, -1) + k_N I / 10 (a
   * pre-stressed string with elastic supports); H(x) = K_N^{-1}(f_0 - K_D x
   * - c x^3), the cubic term (soil stiffening, componentwise) being zero
   * unless @p cubic is set.
   */
  struct VectorModel
  {
    unsigned int       n;
    FullMatrix<double> K_N, K_N_inverse, K_D;
    Vector<double>     f_0;
    double             cubic = 0.;

    VectorModel(const unsigned int n,
                const double       ratio,
                const double       cubic_coefficient = 0.)
      : n(n)
      , K_N(n, n)
      , K_N_inverse(n, n)
      , K_D(n, n)
      , f_0(n)
      , cubic(cubic_coefficient)
    {
      const double k_N = 1e6;
      for (unsigned int i = 0; i < n; ++i)
        {
          K_N(i, i) = 2.1 * k_N;
          if (i > 0)
            K_N(i, i - 1) = K_N(i - 1, i) = -k_N;
          // soil stiffer towards the middle of the net
          K_D(i, i) = ratio * k_N * (0.5 + std::sin(M_PI * (i + 0.5) / n));
        }
      K_N_inverse.invert(K_N);
      set_load(1.);
    }

    /** f_0,i = amplitude * 1e4 N * (1 + i/n). */
    void
    set_load(const double amplitude)
    {
      for (unsigned int i = 0; i < n; ++i)
        f_0[i] = amplitude * 1e4 * (1. + double(i) / n);
    }

    void
    operator()(const Vector<double> &x, Vector<double> &x_tilde) const
    {
      Vector<double> f(f_0);
      Vector<double> kx(n);
      K_D.vmult(kx, x);
      f -= kx;
      for (unsigned int i = 0; i < n; ++i)
        f[i] -= cubic * x[i] * x[i] * x[i];
      x_tilde.reinit(n);
      K_N_inverse.vmult(x_tilde, f);
    }

    /** The load of window @p w of the accelerator tests: its size and
     * shape change from window to window. */
    void
    set_window_load(const unsigned int w)
    {
      for (unsigned int i = 0; i < n; ++i)
        f_0[i] =
          1e4 * (1. + double(i) / n) * (1. + 0.5 * std::sin(0.5 * w + 0.9 * i));
    }

    /** Newton on (K_N + K_D) x + c x^3 = f_0, from x = 0: the monolithic
     * solution the partitioned iterations converge to. */
    Vector<double>
    monolithic_solution() const
    {
      Vector<double> x(n);
      for (unsigned int it = 0; it < 50; ++it)
        {
          FullMatrix<double> J(K_N);
          J.add(1., K_D);
          Vector<double> residual(n), kx(n);
          J.vmult(kx, x);
          for (unsigned int i = 0; i < n; ++i)
            {
              residual[i] = kx[i] + cubic * std::pow(x[i], 3) - f_0[i];
              J(i, i) += 3. * cubic * x[i] * x[i];
            }
          if (residual.l2_norm() <= 1e-13 * f_0.l2_norm())
            break;
          FullMatrix<double> J_inverse(n, n);
          J_inverse.invert(J);
          Vector<double> dx(n);
          J_inverse.vmult(dx, residual);
          x -= dx;
        }
      return x;
    }

    /** Exact solution of the linear model (cubic = 0): (K_N + K_D) x = f_0. */
    Vector<double>
    linear_solution() const
    {
      FullMatrix<double> A(K_N);
      A.add(1., K_D);
      FullMatrix<double> A_inverse(n, n);
      A_inverse.invert(A);
      Vector<double> x(n);
      A_inverse.vmult(x, f_0);
      return x;
    }
  };


  /**
   * The contact solution of the vector model: the active-set solution of
   * K_N x = K_D (s - x) on the nodes with s > x (pressed), 0 elsewhere.
   */
  inline dealii::Vector<double>
  active_set_solution(const VectorModel &m, const dealii::Vector<double> &s)
  {
    const unsigned int     n = s.size();
    std::vector<bool>      active(n, false);
    dealii::Vector<double> x(n);
    for (unsigned int it = 0; it < 50; ++it)
      {
        dealii::FullMatrix<double> A(m.K_N);
        dealii::Vector<double>     b(n);
        for (unsigned int i = 0; i < n; ++i)
          if (active[i])
            {
              A(i, i) += m.K_D(i, i);
              b[i] = m.K_D(i, i) * s[i];
            }
        dealii::FullMatrix<double> A_inverse(n, n);
        A_inverse.invert(A);
        A_inverse.vmult(x, b);
        bool changed = false;
        for (unsigned int i = 0; i < n; ++i)
          if ((s[i] > x[i]) != active[i])
            {
              active[i] = !active[i];
              changed   = true;
            }
        if (!changed)
          break;
      }
    return x;
  }
} // namespace TwoSpring

#endif
