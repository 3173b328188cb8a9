/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   fix wall/gran/servo: rigid plate with a force servo (law/servo.h) in contact with particles
   through the same contact law as pair gran/hertz/rolling (law/contact_chain.h); or a film: a
   two-faced sheet of finite thickness and mass, free to move under the particles' forces.
   This file: init, the contact loop (over a candidate list of the particles near the plate),
   the plate's motion (servo, velocity, free), outputs and restart; the command's arguments are
   read in fix_wall_gran_servo_args.cpp.
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
#include "neighbor.h"
#include "update.h"
#include "variable.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
namespace law = tbags::contact;

// warn when the plate force alternates from step to step by more than this fraction of it
static constexpr double CHATTER_FRACTION = 0.01;

FixWallGranServo::~FixWallGranServo()
{
  if (copymode) return;
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(history);
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

  // a fix adapt may grow radii within a run, which the candidate list would not see
  use_candidates = modify->get_fix_by_style("^adapt").empty();

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
  candidates_built = false;    // the deck may have moved, added or removed particles
  post_force(vflag);
}

void FixWallGranServo::build_candidates()
{
  const double reach = 1.5 * neighbor->skin;
  candidates.clear();
  for (int i = 0; i < atom->nlocal; i++)
    if ((atom->mask[i] & groupbit) && gap(atom->x[i][axis]) - atom->radius[i] < reach)
      candidates.push_back(i);
  pos_built = pos;
  candidates_built = true;
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

  if (use_candidates &&
      (!candidates_built || neighbor->ago == 0 || std::fabs(pos - pos_built) >= 0.5 * neighbor->skin))
    build_candidates();
  const int ncand = use_candidates ? (int) candidates.size() : nlocal;
  for (int k = 0; k < ncand; k++) {
    const int i = use_candidates ? candidates[k] : k;
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
    double vd[3], wd[3];
    if (implicit_damping) {    // i's velocities at the end of the step from the forces so far
      const double hm = 0.5 * dt * force->ftm2v / rmass[i];
      const double hi = hm / (law::SPHERE_INERTIA * radius[i] * radius[i]);
      for (int k = 0; k < 3; k++) {
        vd[k] = v[i][k] + hm * f[i][k];
        wd[k] = omega[i][k] + hi * torque[i][k];
      }
      c.vdi = vd;
      c.wdi = wd;
      c.hm = hm;
    }
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
    // judged against the servo's target, or for a film the force through it (its net force is
    // the small difference of its two faces' forces)
    double reference = mode[axis] == SERVO ? std::fabs(target) : 0.0;
    if (film())
      for (auto &ff : fface)
        reference = std::fmax(reference, std::sqrt(ff[0] * ff[0] + ff[1] * ff[1] + ff[2] * ff[2]));
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
  if (n >= OUT_VELOCITY) return vplate[n - OUT_VELOCITY];
  if (n >= OUT_FACE_PLUS) return fface[(n - OUT_FACE_PLUS) / 3][(n - OUT_FACE_PLUS) % 3];
  if (n < OUT_DISP) return fplate[n - OUT_FORCE];
  if (n < OUT_TARGET) return disp[n - OUT_DISP];
  switch (n) {
    case OUT_TARGET: return target;
    case OUT_ERROR: return normal_force() - target;
    case OUT_CONTACTS: return ncontact;
    case OUT_CONVERGED: return (tol > 0.0 && nconv_count >= nconv) ? 1.0 : 0.0;
    case OUT_POSITION: return pos;
    case OUT_FILTERED: return measured_force();
    default: return chatter.amplitude;    // OUT_CHATTER
  }
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
  double list[REC_SIZE + 2];
  list[0] = std::nan("");
  list[1] = (double) REC_SIZE;
  double *rec = list + 2;
  rec[REC_POS0] = pos0;
  rec[REC_POS] = pos;
  for (int d = 0; d < 3; d++) {
    rec[REC_DISP + d] = disp[d];
    rec[REC_VPLATE + d] = vplate[d];
  }
  rec[REC_INTEGRAL] = servo.integral;
  rec[REC_TARGET] = target;
  rec[REC_NCONV] = (double) nconv_count;
  rec[REC_FILTERED] = servo.filtered;
  rec[REC_PRIMED] = servo.primed ? 1.0 : 0.0;
  if (comm->me == 0) {
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), REC_SIZE + 2, fp);
  }
}

void FixWallGranServo::restart(char *buf)
{
  auto *list = (double *) buf;
  // tbags 0.3 on: a NaN marker and the record's length before the values
  if (std::isnan(list[0])) {
    const int n = (int) list[1];
    list += 2;
    if (n >= REC_SIZE) {
      servo.filtered = list[REC_FILTERED];
      servo.primed = list[REC_PRIMED] != 0.0;
    }
  }
  pos0 = list[REC_POS0];
  pos = list[REC_POS];
  for (int d = 0; d < 3; d++) {
    disp[d] = list[REC_DISP + d];
    if (mode[d] == SERVO || mode[d] == FREE) vplate[d] = list[REC_VPLATE + d];
  }
  servo.integral = list[REC_INTEGRAL];
  if (target_var.empty() && mode[axis] == SERVO) target = list[REC_TARGET];
  nconv_count = (int) list[REC_NCONV];
  // a resumed run continues from a state the plate produced itself (particles it pressed into)
  placed = true;
}

/* ----------------------------------------------------------------------
   per-atom contact history: grows, migrates and restarts with the atoms
------------------------------------------------------------------------- */

double FixWallGranServo::memory_usage()
{
  return (double) atom->nmax * size_history * sizeof(double) +
         (double) candidates.capacity() * sizeof(int);
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
