/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix wall/gran/servo: the command's arguments (the constructor, the film's mass, the coeff and
   motion keywords), each bad value an error naming the keyword and the fix. The plate's physics
   is in fix_wall_gran_servo.cpp.
------------------------------------------------------------------------- */

#include "fix_wall_gran_servo.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "input.h"
#include "memory.h"
#include "update.h"
#include "variable.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
namespace law = tbags::contact;


/* ----------------------------------------------------------------------
   fix ID group wall/gran/servo xplane|yplane|zplane POS SIDE material E nu keyword values ...
     SIDE = +1 (particles on the + side of the plane), -1, or both (a film: needs 'film')
     coeff T friction mu rolling mu_r restitution e [face +1|-1]
                                      (per particle type or range; face: one face of a film)
     film THICKNESS DENSITY           (m, kg/m3; with SIDE both and bounds: the faces are at
                                      POS +- THICKNESS/2, the mass is DENSITY x THICKNESS x the
                                      bounds' area)
     free x|y|z ...                   (components moved by the particles' forces and gravity:
                                      film only)
     velocity x|y|z V                 (m/s, number or v_name)
     servo F gains KP KI vmax VMAX [filter TAU]
                                      (normal force target in N, number or v_name; TAU: time
                                      constant of the low-pass filter on the measured force, s)
     converge TOL N                   (|F - F_target| < TOL |F_target| for N steps)
     bounds LO1 HI1 LO2 HI2           (rectangle in the two tangential axes)
     warn N                           (warn after N steps at vmax)
     damping explicit|implicit        (contact damping against the half step's velocities, as
                                      stock, or against the end of the step's: stable at twice
                                      the time step)
------------------------------------------------------------------------- */

FixWallGranServo::FixWallGranServo(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), history(nullptr)
{
  if (narg < 9)
    error->all(FLERR, "{}: too few arguments; write 'fix ID group wall/gran/servo zplane POS "
               "+1|-1 material E nu coeff TYPE friction mu rolling mu_r restitution e ...'", STYLE);

  vector_flag = 1;
  size_vector = OUT_SIZE;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  dynamic_group_allow = 1;

  const std::string plane = arg[3];
  if (plane == "xplane") axis = 0;
  else if (plane == "yplane") axis = 1;
  else if (plane == "zplane") axis = 2;
  else
    error->all(FLERR, "{}: unknown plane '{}'; use xplane, yplane or zplane", STYLE, plane);
  pos0 = pos = utils::numeric(FLERR, arg[4], false, lmp);
  const std::string side = arg[5];
  if (side == "+1" || side == "1") sense = 1;
  else if (side == "-1") sense = -1;
  else if (side == "both") sense = 0;
  else
    error->all(FLERR, "{}: side must be +1 (particles on the + side), -1, or both (a film), not "
               "'{}'", STYLE, side);

  Eplate = nuplate = -1.0;
  bounded = false;
  half_thick = density = mass = -1.0;
  gvec = nullptr;
  for (int face = 0; face < 2; face++) {
    tmu[face].assign(atom->ntypes + 1, -1.0);
    tmur[face].assign(atom->ntypes + 1, -1.0);
    tcor[face].assign(atom->ntypes + 1, -1.0);
  }
  for (int d = 0; d < 3; d++) {
    mode[d] = FIXED;
    vset[d] = vplate[d] = disp[d] = fplate[d] = fface[0][d] = fface[1][d] = 0.0;
    vvar_index[d] = -1;
  }
  target = 0.0;
  target_index = -1;
  tol = -1.0;
  nconv = 0;
  nconv_count = 0;
  saturated_steps = 0;
  warn_steps = 100000;
  warned = warned_unstable = false;
  placed = false;
  ncontact = 0.0;
  rolling = law::ROLLING_NONE;
  limit_damping = false;
  size_history = 6;

  int iarg = 6;
  while (iarg < narg) {
    const std::string kw = arg[iarg];
    auto need = [&](int n) {
      if (iarg + n >= narg)
        error->all(FLERR, "{}: keyword '{}' needs {} value(s)", STYLE, kw, n);
    };
    if (kw == "material") {
      need(2);
      Eplate = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      nuplate = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (Eplate <= 0.0)
        error->all(FLERR, "{}: plate Young's modulus must be > 0 Pa (got {})", STYLE, Eplate);
      if (nuplate <= -1.0 || nuplate >= 0.5)
        error->all(FLERR, "{}: plate Poisson's ratio must be in (-1, 0.5) (got {})", STYLE, nuplate);
      iarg += 3;
    } else if (kw == "coeff") {
      parse_coeff(narg, arg, iarg);
    } else if (kw == "film") {
      need(2);
      half_thick = 0.5 * utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      density = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (half_thick <= 0.0 || density <= 0.0)
        error->all(FLERR, "{}: film needs a thickness > 0 m and a density > 0 kg/m3 (got {} {})",
                   STYLE, arg[iarg + 1], arg[iarg + 2]);
      iarg += 3;
    } else if (kw == "velocity" || kw == "servo" || kw == "free") {
      parse_motion(narg, arg, iarg);
    } else if (kw == "converge") {
      need(2);
      tol = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      nconv = utils::inumeric(FLERR, arg[iarg + 2], false, lmp);
      if (tol <= 0.0 || nconv < 1)
        error->all(FLERR, "{}: converge needs a tolerance > 0 and a step count >= 1", STYLE);
      iarg += 3;
    } else if (kw == "bounds") {
      need(4);
      for (int k = 0; k < 2; k++) {
        blo[k] = utils::numeric(FLERR, arg[iarg + 1 + 2 * k], false, lmp);
        bhi[k] = utils::numeric(FLERR, arg[iarg + 2 + 2 * k], false, lmp);
        if (bhi[k] <= blo[k]) error->all(FLERR, "{}: bounds need lo < hi", STYLE);
      }
      bounded = true;
      iarg += 5;
    } else if (kw == "warn") {
      need(1);
      warn_steps = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      iarg += 2;
    } else if (kw == "damping") {
      need(1);
      const std::string how = arg[iarg + 1];
      if (how != "explicit" && how != "implicit")
        error->all(FLERR, "{}: damping must be explicit (as stock) or implicit, not '{}'", STYLE,
                   how);
      implicit_damping = how == "implicit";
      iarg += 2;
    } else {
      error->all(FLERR, "{}: unknown keyword '{}'; use material, coeff, film, velocity, servo, "
                 "free, converge, bounds, warn or damping", STYLE, kw);
    }
  }
  if (Eplate < 0.0) error->all(FLERR, "{}: missing 'material E nu' of the plate", STYLE);
  if (film()) init_film();
  else if (half_thick > 0.0)
    error->all(FLERR, "{}: 'film' is for a sheet with particles on both sides: write 'both' as "
               "the side", STYLE);
  else half_thick = 0.0;

  FixWallGranServo::grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < size_history; k++) history[i][k] = 0.0;
}

/* ----------------------------------------------------------------------
   a film: its thickness, density and area (the bounds) give its mass (a servo on a film is
   refused where it is parsed, parse_motion())
------------------------------------------------------------------------- */

void FixWallGranServo::init_film()
{
  if (half_thick <= 0.0)
    error->all(FLERR, "{}: a plate with particles on both sides is a film: give its 'film "
               "THICKNESS DENSITY'", STYLE);
  if (!bounded)
    error->all(FLERR, "{}: a film needs 'bounds LO1 HI1 LO2 HI2' (its area gives its mass and "
               "particles beyond it pass it by)", STYLE);
  mass = density * 2.0 * half_thick * (bhi[0] - blo[0]) * (bhi[1] - blo[1]);
}

/* ----------------------------------------------------------------------
   coeff TYPES friction mu rolling mu_r restitution e [face +1|-1]
------------------------------------------------------------------------- */

void FixWallGranServo::parse_coeff(int narg, char **arg, int &iarg)
{
  if (iarg + 7 >= narg)
    error->all(FLERR, "{}: coeff needs 'TYPES friction mu rolling mu_r restitution e'", STYLE);
  int lo, hi;
  utils::bounds(FLERR, arg[iarg + 1], 1, atom->ntypes, lo, hi, error);
  double mu = -1, mur = -1, e = -1;
  for (int k = iarg + 2; k < iarg + 8; k += 2) {
    const std::string name = arg[k];
    const double val = utils::numeric(FLERR, arg[k + 1], false, lmp);
    if (name == "friction") mu = val;
    else if (name == "rolling") mur = val;
    else if (name == "restitution") e = val;
    else
      error->all(FLERR, "{}: coeff takes friction, rolling and restitution, not '{}'", STYLE, name);
  }
  if (mu < 0.0) error->all(FLERR, "{}: coeff {}: friction must be given and >= 0", STYLE, arg[iarg + 1]);
  if (mur < 0.0) error->all(FLERR, "{}: coeff {}: rolling must be given and >= 0", STYLE, arg[iarg + 1]);
  if (e <= 0.0 || e > 1.0)
    error->all(FLERR, "{}: coeff {}: restitution must be in (0, 1]", STYLE, arg[iarg + 1]);
  iarg += 8;
  int first = 0, last = 1;    // both faces unless one is named
  if (iarg < narg && strcmp(arg[iarg], "face") == 0) {
    if (iarg + 1 >= narg) error->all(FLERR, "{}: coeff ... face needs +1 or -1", STYLE);
    const std::string f = arg[iarg + 1];
    if (f == "+1" || f == "1") last = 0;
    else if (f == "-1") first = 1;
    else error->all(FLERR, "{}: coeff ... face must be +1 or -1, not '{}'", STYLE, f);
    if (!film())
      error->all(FLERR, "{}: coeff ... face is for a film (side 'both'); a one-sided plate has "
                 "one face", STYLE);
    iarg += 2;
  }
  for (int face = first; face <= last; face++)
    for (int t = lo; t <= hi; t++) {
      tmu[face][t] = mu;
      tmur[face][t] = mur;
      tcor[face][t] = e;
    }
}

/* ----------------------------------------------------------------------
   velocity DIM V   |   servo F gains KP KI vmax VMAX   |   servo off   |   free DIM ...
------------------------------------------------------------------------- */

void FixWallGranServo::parse_motion(int narg, char **arg, int &iarg)
{
  const std::string kw = arg[iarg];
  if (kw == "free") {
    if (!film())
      error->all(FLERR, "{}: free motion needs a mass: it is for a film ('both' as the side, "
                 "'film THICKNESS DENSITY' and 'bounds')", STYLE);
    int n = 0;
    for (iarg++; iarg < narg; iarg++, n++) {
      const std::string dim = arg[iarg];
      const int d = dim == "x" ? 0 : dim == "y" ? 1 : dim == "z" ? 2 : -1;
      if (d < 0) break;
      mode[d] = FREE;
    }
    if (n == 0) error->all(FLERR, "{}: free needs one or more of x, y, z", STYLE);
    return;
  }
  if (kw == "velocity") {
    if (iarg + 2 >= narg) error->all(FLERR, "{}: velocity needs a dimension and a value", STYLE);
    const std::string dim = arg[iarg + 1];
    int d = dim == "x" ? 0 : dim == "y" ? 1 : dim == "z" ? 2 : -1;
    if (d < 0) error->all(FLERR, "{}: velocity dimension must be x, y or z, not '{}'", STYLE, dim);
    set_velocity_from(d, arg, iarg + 2);
    iarg += 3;
    return;
  }
  // servo
  if (iarg + 1 >= narg) error->all(FLERR, "{}: servo needs a target force or 'off'", STYLE);
  if (film())
    error->all(FLERR, "{}: a film has no servo (its normal force is the difference of its two "
               "faces' forces); use free or velocity", STYLE);
  if (strcmp(arg[iarg + 1], "off") == 0) {
    mode[axis] = FIXED;
    vplate[axis] = 0.0;
    iarg += 2;
    return;
  }
  const char *t = arg[iarg + 1];
  if (utils::strmatch(t, "^v_")) {
    target_var = t + 2;
  } else {
    target_var.clear();
    target = utils::numeric(FLERR, t, false, lmp);
  }
  iarg += 2;
  // optional gains/vmax (required the first time the servo is set)
  bool gains_set = servo.kp > 0.0, vmax_set = servo.vmax > 0.0;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "gains") == 0) {
      if (iarg + 2 >= narg) error->all(FLERR, "{}: gains needs KP and KI", STYLE);
      servo.kp = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      servo.ki = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (servo.kp <= 0.0 || servo.ki < 0.0)
        error->all(FLERR, "{}: servo gains must be KP > 0 (m/s per N) and KI >= 0 (m/s per N s)",
                   STYLE);
      gains_set = true;
      servo.integral = 0.0;    // new gains start from zero integral (no bump)
      iarg += 3;
    } else if (strcmp(arg[iarg], "vmax") == 0) {
      if (iarg + 1 >= narg) error->all(FLERR, "{}: vmax needs a value", STYLE);
      servo.vmax = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (servo.vmax <= 0.0) error->all(FLERR, "{}: servo vmax must be > 0 m/s", STYLE);
      vmax_set = true;
      iarg += 2;
    } else if (strcmp(arg[iarg], "filter") == 0) {
      if (iarg + 1 >= narg) error->all(FLERR, "{}: filter needs a time constant (s)", STYLE);
      servo.tau = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (servo.tau < 0.0)
        error->all(FLERR, "{}: servo filter time constant must be >= 0 s (0: no filter), got {}",
                   STYLE, servo.tau);
      servo.primed = false;
      iarg += 2;
    } else {
      break;
    }
  }
  if (!gains_set || !vmax_set)
    error->all(FLERR, "{}: servo needs 'gains KP KI' and 'vmax V', e.g. 'servo 5500 gains 1e-6 "
               "1e-4 vmax 0.01'", STYLE);
  mode[axis] = SERVO;
}

void FixWallGranServo::set_velocity_from(int d, char **arg, int iv)
{
  if (utils::strmatch(arg[iv], "^v_")) {
    vvar[d] = arg[iv] + 2;
  } else {
    vvar[d].clear();
    vvar_index[d] = -1;    // (a variable given before no longer applies)
    vset[d] = utils::numeric(FLERR, arg[iv], false, lmp);
  }
  mode[d] = VELOCITY;
  if (vvar[d].empty()) vplate[d] = vset[d];
}
