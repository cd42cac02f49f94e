// The compliant contact law: its force, witnesses, pushing rule and audit potential.
#include "dynamics/model/contact_law.h"

#include <gtest/gtest.h>

#include <cmath>

namespace needle {
namespace {

TEST(ContactLawTest, CompliantForceIsSpringPlusCriticalFractionDashpot) {
  const CompliantContact law(4e8, 0.05, 1.0);
  const double c = 2.0 * 0.05 * std::sqrt(4e8 * 1.0);  // 2ζ√(k m) = 2000 N·s/m
  EXPECT_DOUBLE_EQ(law.ForceDamping(), c);
  EXPECT_DOUBLE_EQ(law.ForceStiffness(), 4e8);
  EXPECT_DOUBLE_EQ(law.Force(1e-6, 0.1), 4e8 * 1e-6 + c * 0.1);
  EXPECT_EQ(law.name(), "compliant");
}

TEST(ContactLawTest, CompliantPushesOnlyWhenTouchingAndPushing) {
  const CompliantContact law(1e8, 0.1, 2.0);
  // Touching and pushing; touching but the dashpot pulls harder than the spring pushes;
  // apart.
  const ContactWitnesses pushing = law.Witnesses(1e-6, 0.0);
  EXPECT_TRUE(law.Pushes(pushing[0] > 0 ? 1 : -1, pushing[1] > 0 ? 1 : -1));
  const ContactWitnesses pulling = law.Witnesses(1e-6, -1.0);
  EXPECT_GT(pulling[0], 0.0);
  EXPECT_LT(pulling[1], 0.0);
  EXPECT_FALSE(law.Pushes(1, -1));
  EXPECT_FALSE(law.Pushes(-1, 1));
  EXPECT_DOUBLE_EQ(law.GatedForce(1e-6, -1.0), 0.0);  // never pulls
  EXPECT_DOUBLE_EQ(law.GatedForce(-1e-6, 1.0), 0.0);  // apart
  EXPECT_FALSE(law.ImpactRate(0.3).has_value());      // velocities continuous
}

TEST(ContactLawTest, PotentialIsTheIntegralOfTheConservativeForce) {
  const CompliantContact law(3e8, 0.0, 1.0);
  for (double g : {-2e-6, 0.0, 1e-6, 5e-6}) {
    const double h = 1e-9;
    EXPECT_NEAR((law.Potential(g + h) - law.Potential(g - h)) / (2 * h), law.ConservativeForce(g),
                1e-6 * std::abs(law.ConservativeForce(g)) + (g == 0.0 ? 0.2 : 1e-9));
    EXPECT_NEAR((law.ConservativeForce(g + h) - law.ConservativeForce(g - h)) / (2 * h),
                law.ConservativeStiffness(g), g == 0.0 ? 1.6e8 : 1e-3);
  }
  EXPECT_EQ(law.Potential(-1e-3), 0.0);
}

TEST(ContactLawTest, InvalidParametersAreRefused) {
  EXPECT_THROW(CompliantContact(0.0, 0.1, 1.0), std::invalid_argument);
  EXPECT_THROW(CompliantContact(1e8, -0.1, 1.0), std::invalid_argument);
  EXPECT_THROW(CompliantContact(1e8, 0.1, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace needle
