// A user project built against the installed package: aligns two clouds with
// pcl::PhaserRegistration, as one would replace SAC-IA.
#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <random>

int main()
{
  // A small asymmetric scene: ground, two walls and a box, sampled at random.
  auto target = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    const float a = u(rng), b = u(rng);
    switch (i % 4) {
    case 0:
      target->push_back({-15 + 30 * a, -10 + 20 * b, -1.5f});
      break;
    case 1:
      target->push_back({12.0f, -8 + 16 * a, -1.5f + 5 * b});
      break;
    case 2:
      target->push_back({-10 + 8 * a, -9.0f, -1.5f + 3 * b});
      break;
    default:
      target->push_back({3 + 3 * a, 5.0f, -1.5f + 2 * b});
    }
  }
  Eigen::Affine3f truth = Eigen::Translation3f(0.8f, -0.5f, 0.0f) *
                          Eigen::AngleAxisf(2.0f, Eigen::Vector3f::UnitZ());
  auto source = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::transformPointCloud(*target, *source, Eigen::Affine3f(truth.inverse()));

  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  phaser.align(aligned);
  const Eigen::Matrix4f T = phaser.getFinalTransformation();
  const float rot_err =
      Eigen::AngleAxisf(
          Eigen::Matrix3f(T.topLeftCorner<3, 3>().transpose() * truth.linear()))
          .angle() *
      180.0f / static_cast<float>(M_PI);
  const float trans_err = (T.topRightCorner<3, 1>() - truth.translation()).norm();
  std::printf(
      "downstream: converged %d, rotation error %.3f deg, translation error %.3f m\n",
      phaser.hasConverged(), rot_err, trans_err);
  return phaser.hasConverged() && rot_err < 1.0f && trans_err < 0.1f ? 0 : 1;
}
