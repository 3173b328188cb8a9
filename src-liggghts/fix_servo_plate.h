/* -*- c++ -*- T-BAGS DEM toolkit, LIGGGHTS adapter: fix servo/plate, the force servo of our
   LAMMPS plate (law/servo.h: PI control of the plate speed on a low-pass filtered force, with a
   speed limit and anti-windup) for a LIGGGHTS mesh plate:
     fix ID all servo/plate v_F target F0 gains KP KI vmax V [filter TAU] [converge TOL N]
   v_F: an equal-style variable, the plate's normal force (compression positive, e.g. from fix
   mesh/surface ... stress on); F0 (N, > 0), KP (m/s per N), KI (m/s per N s), V (m/s), TAU (s).
   Its scalar is the plate's speed toward the particles for the next step, to drive fix move/mesh
   linear/variable (e.g. variable vz equal -f_ID for a top plate); before the first contact
   (F = 0) it is V. Vector: 1 speed, 2 the filtered force, 3 converged (1: |F_f - F0| < TOL F0 for
   N steps), 4 the force error. fix_modify ID target F0 | gains KP KI | vmax V (the filter and the
   integral carry on; new gains restart the integral, as in LAMMPS). Restart: the filter and the
   integral. (LIGGGHTS's own servo mesh module cannot move with fix move/mesh, so it cannot hold
   the normal force of a plate that also moves sideways.) */
#ifdef FIX_CLASS
FixStyle(servo/plate,FixServoPlate)
#else
#ifndef LMP_FIX_SERVO_PLATE_H
#define LMP_FIX_SERVO_PLATE_H

#include "fix.h"
#include "law/servo.h"

#include <string>

namespace LAMMPS_NS {

class FixServoPlate : public Fix {
 public:
  FixServoPlate(class LAMMPS *, int, char **);
  int setmask();
  void init();
  void setup(int);
  void end_of_step();
  double compute_scalar();
  double compute_vector(int);
  int modify_param(int, char **);
  void write_restart(FILE *);
  void restart(char *);

 private:
  tbags::servo::Controller servo;
  std::string force_var;
  int force_index;
  double target, speed, error_now;
  double tol;
  int nconv, nconv_count;
  int parse(int iarg, int narg, char **arg, bool creating);
  void step();
};

}    // namespace LAMMPS_NS
#endif
#endif
