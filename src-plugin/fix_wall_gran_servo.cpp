/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix wall/gran/servo: rigid plate with a force servo (law/servo.h) in contact with particles
   through the same contact law as pair gran/hertz/rolling (law/contact_chain.h); or a film: a
   two-faced sheet of finite thickness and mass, free to move under the particles' forces.
   About 730 lines, more than one job's 500: the keyword parsing with its error messages (about
   330), the contact loop, the plate's motion (servo, velocity, free) and restart; splitting the
   parsing into a file of its own is left for the issue that makes the plates' loop faster.
------------------------------------------------------------------------- */

#include "fix_wall_gran_servo.h"

#include "pair_gran_hertz_rolling.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "memory.h"
#include "modify.h"
#include "update.h"
#include "variable.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
namespace law = tbags::contact;

static const char *STYLE = "Fix wall/gran/servo";
static constexpr int NVECTOR = 22;
// global restart record: a NaN marker, its length, then the values (files of tbags 0.2 and before
// hold 11 values and no marker)
static constexpr int NRESTART = 13;
// warn when the plate force alternates from step to step by more than this fraction of it
static constexpr double CHATTER_FRACTION = 0.01;

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
------------------------------------------------------------------------- */

FixWallGranServo::FixWallGranServo(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), history(nullptr)
{
  if (narg < 9)
    error->all(FLERR, "{}: too few arguments; write 'fix ID group wall/gran/servo zplane POS "
               "+1|-1 material E nu coeff TYPE friction mu rolling mu_r restitution e ...'", STYLE);

  vector_flag = 1;
  size_vector = NVECTOR;
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
    } else {
      error->all(FLERR, "{}: unknown keyword '{}'; use material, coeff, film, velocity, servo, "
                 "free, converge, bounds or warn", STYLE, kw);
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

FixWallGranServo::~FixWallGranServo()
{
  if (copymode) return;
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(history);
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

/* ---------------------------------------------------------------------- */

int FixWallGranServo::setmask()
{
  return POST_FORCE;
}

void FixWallGranServo::init()
{
  dt = update->dt;
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "{} requires atom_style sphere or bpm/sphere", STYLE);
  if (strcmp(update->unit_style, "si") != 0 && comm->me == 0)
    error->warning(FLERR, "{}: E (Pa), forces (N), velocities (m/s) and gains are SI values, but "
                   "this deck uses 'units {}'", STYLE, update->unit_style);

  auto *pair = dynamic_cast<PairGranHertzRolling *>(force->pair_match("gran/hertz/rolling", 1));
  if (!pair)
    error->all(FLERR, "{} takes the particles' materials from pair_style gran/hertz/rolling; "
               "define it (with 'pair_coeff I I material E nu ...') before running", STYLE);
  rolling = pair->rolling_model();
  limit_damping = pair->damping_limited();

  // types present in the group need plate coefficients
  std::vector<int> present(atom->ntypes + 1, 0), all(atom->ntypes + 1, 0);
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) present[atom->type[i]] = 1;
  MPI_Allreduce(present.data(), all.data(), atom->ntypes + 1, MPI_INT, MPI_MAX, world);

  for (int face = 0; face < 2; face++) {
    params[face].assign(atom->ntypes + 1, law::Params());
    if (!has_face(face)) continue;
    for (int t = 1; t <= atom->ntypes; t++) {
      if (tmu[face][t] < 0.0) {
        if (all[t])
          error->all(FLERR, "{}: particles of type {} are in the group but have no {} "
                     "coefficients; add 'coeff {} friction mu rolling mu_r restitution e{}'", STYLE,
                     t, film() ? (face == 0 ? "film (+ face)" : "film (- face)") : "plate", t,
                     film() ? (face == 0 ? " face +1" : " face -1") : "");
        continue;
      }
      const double E = pair->material_E(t), nu = pair->material_nu(t);
      if (E <= 0.0)
        error->all(FLERR, "{}: type {} has no material in pair_style gran/hertz/rolling", STYLE, t);
      params[face][t] = law::make_params(law::mix_E(E, nu, Eplate, nuplate),
                                         law::mix_G(E, nu, Eplate, nuplate), tcor[face][t],
                                         tmu[face][t], tmur[face][t], rolling, limit_damping);
    }
  }
  // a free film feels the deck's gravity (the first fix gravity), as its particles do
  gvec = nullptr;
  if (film()) {
    const double *lo = domain->boxlo, *hi = domain->boxhi;
    if (pos - half_thick < lo[axis] || pos + half_thick > hi[axis])
      error->all(FLERR, "{} {}: the film ({} to {} m) is outside the box ({} to {} m along its "
                 "normal); place it between the particles it separates", STYLE, id,
                 pos - half_thick, pos + half_thick, lo[axis], hi[axis]);

    auto grav = modify->get_fix_by_style("^gravity");
    if (!grav.empty()) {
      int dim = 0;
      gvec = static_cast<const double *>(grav[0]->extract("gvec", dim));
    }
    if (comm->me == 0 && !placed)
      utils::logmesg(lmp, "{} {}: film of mass {:.6g} kg, {}\n", STYLE, id, mass,
                     gvec ? "weight from fix " + std::string(grav[0]->id) : std::string("no gravity"));
  }

  for (int d = 0; d < 3; d++) {
    if (mode[d] == VELOCITY && !vvar[d].empty()) {
      vvar_index[d] = input->variable->find(vvar[d].c_str());
      if (vvar_index[d] < 0 || !input->variable->equalstyle(vvar_index[d]))
        error->all(FLERR, "{}: velocity variable {} does not exist or is not equal-style", STYLE, vvar[d]);
    }
  }
  if (!target_var.empty()) {
    target_index = input->variable->find(target_var.c_str());
    if (target_index < 0 || !input->variable->equalstyle(target_index))
      error->all(FLERR, "{}: servo target variable {} does not exist or is not equal-style", STYLE,
                 target_var);
  }
}

/* ---------------------------------------------------------------------- */

void FixWallGranServo::setup(int vflag)
{
  // a plate that starts deep inside particles would launch them: refuse. Checked once, at the
  // first run after the fix is defined, and not when its state comes from a restart file: later
  // runs continue from states the plate produced itself or that the deck made on purpose (radii
  // grown against the plate, a changed modulus).
  if (!placed) check_placement();
  placed = true;
  post_force(vflag);
}

void FixWallGranServo::check_placement()
{
  double worst = 0.0, all = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double h = gap(atom->x[i][axis]);
    if (h < atom->radius[i]) worst = MAX(worst, (atom->radius[i] - h) / atom->radius[i]);
  }
  MPI_Allreduce(&worst, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (all > 0.05)
    error->all(FLERR, "{} {}: the plate starts {:.3g} radii inside a particle; place it at least "
               "one radius from the particle centres", STYLE, id, all);
}

/* ---------------------------------------------------------------------- */

void FixWallGranServo::post_force(int)
{
  const bool update_hist = update->setupflag == 0;
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  const double *radius = atom->radius;
  const double *rmass = atom->rmass;
  const int *mask = atom->mask;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
  const double wzero[3] = {0.0, 0.0, 0.0};

  // force on the plate from the + side (3) and the - side (3), contacts
  double floc[7] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  law::Contact c;
  c.wall = true;
  c.radj = 0.0;
  c.vj = vplate;
  c.wj = wzero;
  c.dt = dt;
  law::Result o;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double h = gap(x[i][axis]);
    bool touch = h < radius[i];
    if (touch && bounded) {
      const double a = x[i][t1] - disp[t1], b = x[i][t2] - disp[t2];
      touch = a >= blo[0] && a <= bhi[0] && b >= blo[1] && b <= bhi[1];
    }
    if (!touch) {
      for (int k = 0; k < size_history; k++) history[i][k] = 0.0;
      continue;
    }
    if (h <= 0.0)
      error->one(FLERR, "{} {}: particle {} crossed the {}; reduce the timestep or the plate "
                 "speed (vmax){}", STYLE, id, atom->tag[i], film() ? "film" : "plate",
                 film() ? ", or make the film's bounds wider than the particles around it" : "");
    const int face = face_of(x[i][axis]);
    double dx[3] = {0.0, 0.0, 0.0};
    dx[axis] = face == 0 ? h : -h;
    c.dx = dx;
    c.reff = c.radi = radius[i];
    c.meff = rmass[i];
    c.vi = v[i];
    c.wi = omega[i];
    law::compute(params[face][type[i]], c, history[i], update_hist, o);
    for (int k = 0; k < 3; k++) {
      f[i][k] += o.f[k];
      torque[i][k] += o.ti[k];
      floc[3 * face + k] -= o.f[k];
    }
    floc[6] += 1.0;
  }
  double fall[7];
  MPI_Allreduce(floc, fall, 7, MPI_DOUBLE, MPI_SUM, world);
  for (int k = 0; k < 3; k++) {
    fface[0][k] = fall[k];
    fface[1][k] = fall[3 + k];
    fplate[k] = fall[k] + fall[3 + k];
  }
  ncontact = fall[6];

  if (update_hist) {
    if (ncontact > 0.0) chatter.add(fplate);
    else chatter.reset();
    const double reference = mode[axis] == SERVO ? std::fabs(target) : 0.0;
    if (chatter.chattering(CHATTER_FRACTION, reference) && !warned_unstable && comm->me == 0) {
      error->warning(FLERR, "{} {}: the plate force alternates from step to step by {:.3g} N "
                     "({:.2g} % of it, over the last {} steps): its contacts are at the edge of "
                     "the time step's numerical stability; reduce the timestep", STYLE, id,
                     chatter.amplitude, 100.0 * chatter.amplitude / chatter.magnitude,
                     (int) (1.0 / chatter.RATE));
      warned_unstable = true;
    }
    update_plate();
  }
}

/* ----------------------------------------------------------------------
   plate velocity for the next step (identical on all ranks: inputs are global) and motion
------------------------------------------------------------------------- */

void FixWallGranServo::update_plate()
{
  if (target_index >= 0) target = input->variable->compute_equal(target_index);
  for (int d = 0; d < 3; d++) {
    if (mode[d] == FIXED) {
      vplate[d] = 0.0;
    } else if (mode[d] == VELOCITY) {
      vplate[d] = vvar_index[d] >= 0 ? input->variable->compute_equal(vvar_index[d]) : vset[d];
    } else if (mode[d] == FREE) {    // m dv/dt = F + m g (symplectic Euler, as the particles')
      vplate[d] += (fplate[d] / mass + (gvec ? gvec[d] : 0.0)) * dt;
    } else {    // SERVO: inward speed from the force error
      // no contact yet: approach at vmax without integrating (no wind-up across the gap)
      bool sat = true;
      double vin = servo.vmax;
      if (ncontact > 0.0) {
        vin = servo.velocity(target - servo.measure(normal_force(), dt), dt, sat);
      } else {
        servo.integral = 0.0;
        servo.primed = false;
      }
      vplate[d] = sense * vin;
      saturated_steps = (sat && vin > 0.0) ? saturated_steps + 1 : 0;
      if (saturated_steps > warn_steps && !warned && comm->me == 0) {
        error->warning(FLERR, "{} {}: the plate has moved at vmax toward the particles for {} "
                       "steps without reaching {} N (now {} N); raise vmax, start the plate "
                       "closer, or check the target", STYLE, id, saturated_steps, target,
                       normal_force());
        warned = true;
      }
    }
  }
  if (tol > 0.0) {
    if (std::fabs(measured_force() - target) < tol * std::fabs(target)) nconv_count++;
    else nconv_count = 0;
  }
  pos += vplate[axis] * dt;
  for (int d = 0; d < 3; d++) disp[d] += vplate[d] * dt;
}

/* ----------------------------------------------------------------------
   1-3 force of the particles on the plate, 4-6 displacement since creation, 7 target,
   8 normal force - target, 9 contacts, 10 converged (1/0), 11 plate position,
   12 the normal force the servo sees (filtered), 13 the part of the force that alternates from
   step to step (N, averaged over about 1000 steps; near 0 for a stable time step),
   14-16 the force of the particles on the + side, 17-19 of those on the - side (their sum is
   1-3), 20-22 the plate's velocity for the next step
------------------------------------------------------------------------- */

double FixWallGranServo::compute_vector(int n)
{
  if (n >= 19) return vplate[n - 19];
  if (n >= 13) return fface[(n - 13) / 3][(n - 13) % 3];
  if (n < 3) return fplate[n];
  if (n < 6) return disp[n - 3];
  if (n == 6) return target;
  if (n == 7) return normal_force() - target;
  if (n == 8) return ncontact;
  if (n == 9) return (tol > 0.0 && nconv_count >= nconv) ? 1.0 : 0.0;
  if (n == 10) return pos;
  if (n == 11) return measured_force();
  return chatter.amplitude;
}

/* ----------------------------------------------------------------------
   fix_modify ID velocity DIM V | servo F [gains KP KI] [vmax V] | servo off | free DIM ...
------------------------------------------------------------------------- */

int FixWallGranServo::modify_param(int narg, char **arg)
{
  if (strcmp(arg[0], "velocity") != 0 && strcmp(arg[0], "servo") != 0 && strcmp(arg[0], "free") != 0)
    return 0;
  int iarg = 0;
  parse_motion(narg, arg, iarg);
  nconv_count = 0;
  warned = warned_unstable = false;
  saturated_steps = 0;
  return iarg;    // variables are resolved by init() at the next run

}

/* ---------------------------------------------------------------------- */

void FixWallGranServo::reset_dt()
{
  dt = update->dt;
}

void FixWallGranServo::write_restart(FILE *fp)
{
  double list[NRESTART + 2] = {std::nan(""), (double) NRESTART, pos0, pos, disp[0], disp[1],
                               disp[2], vplate[0], vplate[1], vplate[2], servo.integral, target,
                               (double) nconv_count, servo.filtered, servo.primed ? 1.0 : 0.0};
  if (comm->me == 0) {
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), NRESTART + 2, fp);
  }
}

void FixWallGranServo::restart(char *buf)
{
  auto *list = (double *) buf;
  // tbags 0.3 on: a NaN marker and the record's length before the values
  if (std::isnan(list[0])) {
    const int n = (int) list[1];
    list += 2;
    if (n >= NRESTART) {
      servo.filtered = list[11];
      servo.primed = list[12] != 0.0;
    }
  }
  pos0 = list[0];
  pos = list[1];
  for (int d = 0; d < 3; d++) {
    disp[d] = list[2 + d];
    if (mode[d] == SERVO || mode[d] == FREE) vplate[d] = list[5 + d];
  }
  servo.integral = list[8];
  if (target_var.empty() && mode[axis] == SERVO) target = list[9];
  nconv_count = (int) list[10];
  // a resumed run continues from a state the plate produced itself (particles it pressed into)
  placed = true;
}

/* ----------------------------------------------------------------------
   per-atom contact history: grows, migrates and restarts with the atoms
------------------------------------------------------------------------- */

double FixWallGranServo::memory_usage()
{
  return (double) atom->nmax * size_history * sizeof(double);
}

void FixWallGranServo::grow_arrays(int nmax)
{
  memory->grow(history, nmax, size_history, "wall/gran/servo:history");
}

void FixWallGranServo::copy_arrays(int i, int j, int)
{
  for (int m = 0; m < size_history; m++) history[j][m] = history[i][m];
}

void FixWallGranServo::set_arrays(int i)
{
  for (int m = 0; m < size_history; m++) history[i][m] = 0.0;
}

int FixWallGranServo::pack_exchange(int i, double *buf)
{
  for (int m = 0; m < size_history; m++) buf[m] = history[i][m];
  return size_history;
}

int FixWallGranServo::unpack_exchange(int nlocal, double *buf)
{
  for (int m = 0; m < size_history; m++) history[nlocal][m] = buf[m];
  return size_history;
}

int FixWallGranServo::pack_restart(int i, double *buf)
{
  buf[0] = size_history + 1;
  for (int m = 0; m < size_history; m++) buf[m + 1] = history[i][m];
  return size_history + 1;
}

void FixWallGranServo::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  for (int k = 0; k < size_history; k++) history[nlocal][k] = extra[nlocal][m++];
}

int FixWallGranServo::size_restart(int)
{
  return size_history + 1;
}

int FixWallGranServo::maxsize_restart()
{
  return size_history + 1;
}
