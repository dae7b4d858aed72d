// What the joint drive suites read off a trajectory: the damped oscillation a sequence of
// coordinates c_n (one a step of h) follows, from the least-squares fit of
// c_{n+1} = T c_n − D c_{n−1} + E: the eigenvalue z = e^{λh} of z² − T z + D gives
// ω = |λ| and ζ = −Re λ / |λ|, and the centre is E / (1 − T + D).
#pragma once

#include <Eigen/Dense>

#include <complex>
#include <vector>

namespace tumble::test {

struct Oscillation {
    double omega = 0.0, zeta = 0.0, centre = 0.0;
};

inline Oscillation fitOscillation(const std::vector<double>& c, double h) {
    const int n = static_cast<int>(c.size()) - 2;
    Eigen::MatrixXd M(n, 3);
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) {
        M.row(i) << c[i + 1], -c[i], 1.0;
        y[i] = c[i + 2];
    }
    const Eigen::Vector3d p = M.colPivHouseholderQr().solve(y);
    const double T = p[0], D = p[1];
    const std::complex<double> z = 0.5 * (T + std::sqrt(std::complex<double>(T * T - 4.0 * D)));
    const std::complex<double> lambda = std::log(z) / h;
    return {std::abs(lambda), -lambda.real() / std::abs(lambda), p[2] / (1.0 - T + D)};
}

}  // namespace tumble::test
