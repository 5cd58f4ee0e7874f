#include "export/takeoff.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/geoid.h"

namespace cinepath::exporter {
namespace {

// Level ground at `up_m` (ENU of the scene's origin) within 100 m of the origin.
class FlatGround : public Ground {
 public:
  explicit FlatGround(double up_m) : up_m_(up_m) {}
  std::optional<double> SurfaceUpM(double east_m, double north_m, double) const override {
    if (std::abs(east_m) > 100 || std::abs(north_m) > 100) return std::nullopt;
    return up_m_;
  }
  const std::string& source() const override { return name_; }

 private:
  double up_m_;
  std::string name_ = "flat.glb";
};

const Geodetic kScene{46.842656667, -91.994008025, 198.5534};

TEST(Takeoff, HomeIsTheGroundUnderTheFirstSample) {
  Trajectory plan;
  plan.samples.emplace_back();
  plan.samples[0].position_enu_m = Eigen::Vector3d(20, -10, -25);
  const FlatGround ground(-35.5);
  const HomeSpec home = TakeoffOnGround(plan, kScene, ground);
  const EnuFrame frame(kScene);
  const double ellipsoidal = Egm96Geoid::Default().EllipsoidalFromAmslM(home.lat_deg, home.lon_deg, home.amsl_m);
  const Eigen::Vector3d enu = frame.EnuFromGeodetic(Geodetic{home.lat_deg, home.lon_deg, ellipsoidal});
  EXPECT_LT((enu - Eigen::Vector3d(20, -10, -35.5)).norm(), 1e-6);
  // The check finds no difference for that home, and the difference for one 10 m higher.
  EXPECT_NEAR(CheckHomeAgainstGround(home, kScene, ground)->difference_m, 0, 1e-6);
  EXPECT_NEAR(
      CheckHomeAgainstGround(HomeSpec{home.lat_deg, home.lon_deg, home.amsl_m + 10}, kScene, ground)->difference_m, 10,
      1e-6);
}

TEST(Takeoff, APlanAboutAnotherOriginTakesOffUnderItsFirstSample) {
  Trajectory plan;
  plan.origin = Geodetic{46.84265, -91.99445, 153.0};  // 34 m west of the scene's origin
  plan.samples.emplace_back();
  plan.samples[0].position_enu_m = Eigen::Vector3d(40, 0, 10);
  const HomeSpec home = TakeoffOnGround(plan, kScene, FlatGround(-35.5));
  const Eigen::Vector3d plan_enu = EnuFrame(*plan.origin)
                                       .EnuFromGeodetic(Geodetic{home.lat_deg, home.lon_deg,
                                                                 Egm96Geoid::Default().EllipsoidalFromAmslM(
                                                                     home.lat_deg, home.lon_deg, home.amsl_m)});
  EXPECT_NEAR(plan_enu.x(), 40, 1e-3);
  EXPECT_NEAR(plan_enu.y(), 0, 1e-3);
}

TEST(Takeoff, NoGroundUnderTheFirstSampleIsAnInputError) {
  Trajectory plan;
  plan.samples.emplace_back();
  plan.samples[0].position_enu_m = Eigen::Vector3d(500, 0, 10);
  EXPECT_THROW(TakeoffOnGround(plan, kScene, FlatGround(0)), InputError);
  EXPECT_FALSE(CheckHomeAgainstGround(HomeSpec{46.9, -91.99, 190}, kScene, FlatGround(0)));
}

}  // namespace
}  // namespace cinepath::exporter
