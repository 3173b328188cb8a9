// The plate servo (law/servo.h): the force filter and the chatter meter, against exact answers.
#include "law/servo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using tbags::servo::Chatter;
using tbags::servo::Controller;

TEST(Servo, NoFilterPassesTheForce)
{
  Controller c;
  for (double F : {3.0, -2.0, 7.5}) EXPECT_EQ(c.measure(F, 1e-6), F);
}

TEST(Servo, FilterIsFirstOrderLowPass)
{
  // a step from 0 to 1 after priming at 0: F_f(n) = 1 - (1 - alpha)^n, alpha = dt / (tau + dt)
  Controller c;
  c.tau = 9e-6;
  const double dt = 1e-6, alpha = 0.1;
  c.measure(0.0, dt);
  for (int n = 1; n <= 50; n++) EXPECT_NEAR(c.measure(1.0, dt), 1.0 - std::pow(1.0 - alpha, n), 1e-14);
}

TEST(Servo, FirstMeasurementPrimesTheFilter)
{
  Controller c;
  c.tau = 1e-3;
  EXPECT_EQ(c.measure(318.0, 1e-6), 318.0);    // no ramp from zero
  c.primed = false;
  EXPECT_EQ(c.measure(42.0, 1e-6), 42.0);
}

TEST(Servo, ChatterMeterIsExactForAnAlternatingForce)
{
  Chatter m;
  const double A = 3.0;
  for (int n = 0; n < 5000; n++) {
    const double s = (n % 2) ? -1.0 : 1.0;
    const double f[3] = {100.0 + 0.01 * n + A * s, -50.0, 318.0 - 0.5 * A * s};
    m.add(f);
  }
  EXPECT_NEAR(m.amplitude, A * std::sqrt(1.25), 1e-9);
  EXPECT_TRUE(m.chattering(0.005));            // 3.35 N of |F| = 355 N
  EXPECT_FALSE(m.chattering(0.005, 1000.0));   // small against a large reference force
}

TEST(Servo, ChatterMeterIgnoresSmoothForces)
{
  Chatter m;
  for (int n = 0; n < 5000; n++) {
    const double t = n * 1e-6;
    const double f[3] = {500.0 * t * 1e3, 300.0 + 20.0 * std::sin(2 * 3.14159265 * 50 * t), 0.0};
    m.add(f);
  }
  EXPECT_LT(m.amplitude, 1e-3);
  EXPECT_FALSE(m.chattering(0.01));
}

TEST(Servo, ChatterMeterWaitsForAFullWindow)
{
  Chatter m;
  for (int n = 0; n < 500; n++) {
    const double f[3] = {(n % 2) ? 1.0 : -1.0, 0.0, 0.0};
    m.add(f);
  }
  EXPECT_NEAR(m.amplitude, 1.0, 1e-12);
  EXPECT_FALSE(m.chattering(0.01));    // only 500 of the 1000 steps
  m.reset();
  EXPECT_EQ(m.count, 0);
  EXPECT_EQ(m.amplitude, 0.0);
}

// A force with noise of no fixed phase (contacts making and breaking, grains landing on the bag)
// is not chatter: before the coherent mean, white noise of amplitude s read as 0.6 s, so a
// packing's first contacts warned "reduce the timestep" at any step.
TEST(Servo, ChatterMeterIgnoresNoiseWithoutAPhase)
{
  Chatter m;
  std::mt19937 gen(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 20000; n++) {
    const double kick = u(gen) < 0.01 ? 10.0 : 0.0;    // an impact every 100 steps or so
    const double f[3] = {noise(gen), 0.5 * noise(gen), 100.0 + noise(gen) + kick};
    m.add(f);
  }
  EXPECT_LT(m.amplitude, 0.1);    // the noise's sd is 1 N (the old meter: about 1 N)
  EXPECT_FALSE(m.chattering(0.005));
}
