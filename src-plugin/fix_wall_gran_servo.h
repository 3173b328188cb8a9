/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix wall/gran/servo: a rigid plane plate, in contact with particles through
   law/contact_law.h, moved at prescribed velocities or by a force servo.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_SERVO_H
#define LMP_FIX_WALL_GRAN_SERVO_H

#include "fix.h"
#include "law/contact_law.h"
#include "law/servo.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixWallGranServo : public Fix {
 public:
  FixWallGranServo(class LAMMPS *, int, char **);
  ~FixWallGranServo() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  double compute_vector(int) override;
  int modify_param(int, char **) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  void reset_dt() override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

 protected:
  int axis;              // 0,1,2: plane normal along x, y, z
  int sense;             // +1: particles on the + side of the plane, -1: on the - side
  double pos0, pos;      // plane position at creation and now
  double disp[3];        // plate displacement since creation (u, w)
  double vplate[3];      // plate velocity used this step
  double Eplate, nuplate;
  bool bounded;
  double blo[2], bhi[2];    // rectangle in the two tangential axes (moves with the plate)

  // per particle type: friction, rolling friction, restitution (-1 = not given)
  std::vector<double> tmu, tmur, tcor;
  std::vector<tbags::contact::Params> params;    // per type, built in init()
  int rolling;
  bool limit_damping;
  int size_history;
  double **history;

  // motion of each component: FIXED, VELOCITY (number or variable) or SERVO (normal only)
  enum { FIXED = 0, VELOCITY = 1, SERVO = 2 };
  int mode[3];
  double vset[3];
  std::string vvar[3];
  int vvar_index[3];
  tbags::servo::Controller servo;
  std::string target_var;
  int target_index;
  double target;         // current target force (N, compression positive)

  // convergence: |F - target| < tol * |target| for nconv consecutive steps
  double tol;
  int nconv, nconv_count;
  bigint saturated_steps, warn_steps;
  bool warned, warned_unstable;
  tbags::servo::Chatter chatter;    // step-to-step alternation of the plate force
  bool placed;    // the start-position check ran (first setup after the fix was defined)

  double fplate[3];      // force of the particles on the plate (summed over ranks)
  double ncontact;
  double dt;

  void parse_motion(int, char **, int &);
  void set_velocity_from(int, char **, int);
  double normal_force() const { return -sense * fplate[axis]; }
  // the normal force the servo acts on: filtered once it has measured (as normal_force() with
  // no filter)
  double measured_force() const
  {
    return (mode[axis] == SERVO && servo.primed) ? servo.filtered : normal_force();
  }
  void update_plate();
  void check_placement();
};

}    // namespace LAMMPS_NS

#endif
