// Uses the installed engine: recovers a rotation between two spherical signals.
#include <pcl_phaser/core/so3_correlation.h>
#include <pcl_phaser/core/so3_refinement.h>
#include <pcl_phaser/core/spherical_grid.h>
#include <pcl_phaser/core/spherical_harmonics.h>

#include <cmath>
#include <cstdio>
#include <vector>

int main()
{
  using namespace pcl_phaser;
  const int B = 16, n = 2 * B;
  const Eigen::Matrix3d R = rotationFromEuler({0.5, 1.0, -0.7});
  const Eigen::Vector3d lobes[] = {
      {1, 0, 0}, {0, 0.6, 0.8}, {-0.6, -0.8, 0}, {0, 0, -1}};
  std::vector<double> f(n * n), h(n * n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d w = sampleDirection(j, k, B);
        h[j * n + k] += (1 + i) * std::exp(10 * (w.dot(lobes[i]) - 1));
        f[j * n + k] += (1 + i) * std::exp(10 * (w.dot(R * lobes[i]) - 1));
      }
  const auto sht = SphericalHarmonicTransform::instance(B);
  const SphericalSpectrum F = sht->forward(f.data()), H = sht->forward(h.data());
  const So3CorrelationGrid C = So3Correlator::instance(B)->correlate(F, H);
  const Eigen::Matrix3d est =
      refineRotation(F, H, rotationFromEuler(gridEuler(C.argmax(), B)), B).rotation;
  const double err = rotationDistance(est, R) * 180 / M_PI;
  std::printf("downstream: rotation error %.5f deg\n", err);
  return err < 0.01 ? 0 : 1;
}
