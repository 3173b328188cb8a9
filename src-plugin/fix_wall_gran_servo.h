/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix wall/gran/servo: a rigid plane plate, in contact with particles through
   law/contact_law.h, moved at prescribed velocities, by a force servo, or free under the
   particles' forces (a film: two faces, a thickness and a mass).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_SERVO_H
#define LMP_FIX_WALL_GRAN_SERVO_H

#include "fix.h"
#include "law/contact_chain.h"
#include "law/servo.h"

#include <cmath>
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
  static constexpr const char *STYLE = "Fix wall/gran/servo";    // errors' prefix
  int axis;              // 0,1,2: plane normal along x, y, z
  int sense;             // +1: particles on the + side of the plane, -1: on the - side, 0: both
                         // (a film: two faces, each a half-thickness from the mid-plane)
  double half_thick;     // film: half its thickness (0 for a one-sided plate)
  double density, mass;  // film: density (kg/m3) and mass (density x thickness x bounds area)
  const double *gvec;    // film: acceleration of fix gravity (nullptr: none)
  double pos0, pos;      // plane position at creation and now
  double disp[3];        // plate displacement since creation (u, w)
  double vplate[3];      // plate velocity used this step
  double Eplate, nuplate;
  bool bounded;
  double blo[2], bhi[2];    // rectangle in the two tangential axes (moves with the plate)

  // per face (0: the + side, 1: the - side) and particle type: friction, rolling friction,
  // restitution (-1 = not given)
  std::vector<double> tmu[2], tmur[2], tcor[2];
  std::vector<tbags::contact::Params> params[2];    // per face and type, built in init()
  int rolling;
  bool limit_damping;
  bool implicit_damping = false;    // 'damping implicit' (law::Contact::hm)
  int size_history;
  double **history;

  // the particles that can touch the plate (local indices, in order): those within 1.5 neighbor
  // skins of it (gap - radius) when the list was built. Rebuilt at every reneighboring and when
  // the plate has moved half a skin since: a particle moves less than a skin between builds
  // (each position within half a skin of the last reneighboring's), so a particle left out stays
  // clear of the plate. Not used (all particles every step) when a fix adapt may change radii.
  std::vector<int> candidates;
  bool use_candidates = true, candidates_built = false;
  double pos_built = 0.0;
  void build_candidates();

  // motion of each component: FIXED, VELOCITY (number or variable), SERVO (normal only) or FREE
  // (a film: accelerated by the particles' forces and gravity)
  enum { FIXED = 0, VELOCITY = 1, SERVO = 2, FREE = 3 };
  // compute_vector()'s elements, 0-based (doc/fix_wall_gran_servo.rst numbers them from 1)
  enum Output : int {
    OUT_FORCE = 0,         // 3: the particles' force on the plate
    OUT_DISP = 3,          // 3: the plate's displacement since creation
    OUT_TARGET = 6,        // the servo's target
    OUT_ERROR = 7,         // normal force - target
    OUT_CONTACTS = 8,      // touching particles
    OUT_CONVERGED = 9,     // 1 when converged
    OUT_POSITION = 10,     // the plate's position
    OUT_FILTERED = 11,     // the normal force the servo acts on
    OUT_CHATTER = 12,      // the part of the force that alternates from step to step
    OUT_FACE_PLUS = 13,    // 3: the force of the particles on the + side
    OUT_FACE_MINUS = 16,   // 3: on the - side
    OUT_VELOCITY = 19,     // 3: the plate's velocity for the next step
    OUT_SIZE = 22
  };
  // the global restart record's values, after its NaN marker and length (files of tbags 0.2
  // and before: the first 11, no marker)
  enum Record : int {
    REC_POS0 = 0, REC_POS = 1, REC_DISP = 2, REC_VPLATE = 5, REC_INTEGRAL = 8, REC_TARGET = 9,
    REC_NCONV = 10, REC_FILTERED = 11, REC_PRIMED = 12, REC_SIZE = 13
  };
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
  double fface[2][3];    // the same from the particles on the + side (0) and the - side (1)
  double ncontact;
  double dt;

  void parse_motion(int, char **, int &);
  void parse_coeff(int, char **, int &);
  bool film() const { return sense == 0; }
  // a particle centre at c (along the normal) faces face 0 (the + side) or 1, at gap() from it
  int face_of(double c) const { return sense ? (sense > 0 ? 0 : 1) : (c >= pos ? 0 : 1); }
  double gap(double c) const { return sense ? sense * (c - pos) : std::fabs(c - pos) - half_thick; }
  // the faces this plate has: 0 (+ side) and/or 1 (- side)
  bool has_face(int face) const { return sense == 0 || (face == 0) == (sense > 0); }
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
  void init_film();
};

}    // namespace LAMMPS_NS

#endif
