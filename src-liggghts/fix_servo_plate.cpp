/* T-BAGS DEM toolkit, LIGGGHTS adapter: fix servo/plate (see the header). */

#include "fix_servo_plate.h"

#include "parse_words.h"

#include "comm.h"
#include "error.h"
#include "input.h"
#include "update.h"
#include "variable.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

static const char STYLE[] = "fix servo/plate";

// a whole word as a finite number, or stop naming the keyword
static double number(Error *error, const char *kw, const char *w)
{
  double x;
  if (!tbags::to_number(w, x)) {
    char msg[256];
    snprintf(msg, sizeof(msg), "%s: %s needs a number, got '%s'", STYLE, kw, w);
    error->all(FLERR, msg);
  }
  return x;
}

FixServoPlate::FixServoPlate(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), force_index(-1), target(0.0), speed(0.0), error_now(0.0), tol(-1.0),
  nconv(0), nconv_count(0)
{
  if (narg < 4 || strncmp(arg[3], "v_", 2) != 0)
    error->all(FLERR, "fix servo/plate: write 'fix ID all servo/plate v_F target F0 gains KP KI "
               "vmax V [filter TAU] [converge TOL N]' (v_F: the plate's normal force)");
  force_var = arg[3] + 2;
  scalar_flag = vector_flag = 1;
  size_vector = 4;
  global_freq = 1;
  extscalar = extvector = 0;
  restart_global = 1;
  parse(4, narg, arg, true);
}

// target, gains, vmax, filter, converge; returns the arguments used
int FixServoPlate::parse(int iarg, int narg, char **arg, bool creating)
{
  const int first = iarg;
  while (iarg < narg) {
    const char *kw = arg[iarg];
    const int need = strcmp(kw, "gains") == 0 || strcmp(kw, "converge") == 0 ? 2 : 1;
    if (strcmp(kw, "target") && strcmp(kw, "gains") && strcmp(kw, "vmax") && strcmp(kw, "filter") &&
        strcmp(kw, "converge")) {
      if (!creating) break;
      char msg[256];
      snprintf(msg, sizeof(msg), "%s: unknown keyword '%s'; use target, gains, vmax, filter or converge", STYLE, kw);
      error->all(FLERR, msg);
    }
    if (iarg + need >= narg) {
      char msg[256];
      snprintf(msg, sizeof(msg), "%s: %s needs %d value(s)", STYLE, kw, need);
      error->all(FLERR, msg);
    }
    if (strcmp(kw, "target") == 0) {
      target = number(error, kw, arg[iarg + 1]);
      if (target <= 0.0) error->all(FLERR, "fix servo/plate: the target force must be > 0 N (compression)");
    } else if (strcmp(kw, "gains") == 0) {
      servo.kp = number(error, kw, arg[iarg + 1]);
      servo.ki = number(error, kw, arg[iarg + 2]);
      if (servo.kp <= 0.0 || servo.ki < 0.0)
        error->all(FLERR, "fix servo/plate: gains must be KP > 0 (m/s per N) and KI >= 0 (m/s per N s)");
      servo.integral = 0.0;    // new gains start from zero integral (no bump)
    } else if (strcmp(kw, "vmax") == 0) {
      servo.vmax = number(error, kw, arg[iarg + 1]);
      if (servo.vmax <= 0.0) error->all(FLERR, "fix servo/plate: vmax must be > 0 m/s");
    } else if (strcmp(kw, "filter") == 0) {
      servo.tau = number(error, kw, arg[iarg + 1]);
      if (servo.tau < 0.0) error->all(FLERR, "fix servo/plate: the filter's time constant must be >= 0 s");
    } else {
      tol = number(error, kw, arg[iarg + 1]);
      nconv = atoi(arg[iarg + 2]);
      if (tol <= 0.0 || nconv < 1)
        error->all(FLERR, "fix servo/plate: converge needs a tolerance > 0 and a step count >= 1");
    }
    iarg += need + 1;
  }
  if (creating && (target <= 0.0 || servo.kp <= 0.0 || servo.vmax <= 0.0))
    error->all(FLERR, "fix servo/plate: needs 'target F0', 'gains KP KI' and 'vmax V'");
  nconv_count = 0;
  return iarg - first;
}

int FixServoPlate::setmask()
{
  return END_OF_STEP;
}

void FixServoPlate::init()
{
  force_index = input->variable->find(const_cast<char *>(force_var.c_str()));
  if (force_index < 0 || !input->variable->equalstyle(force_index)) {
    char msg[256];
    snprintf(msg, sizeof(msg), "%s: v_%s is not an equal-style variable", STYLE, force_var.c_str());
    error->all(FLERR, msg);
  }
}

// a run's set-up keeps the speed (0 at first, as the LAMMPS plate's: it moves from the first
// step's forces on)
void FixServoPlate::setup(int) {}

void FixServoPlate::end_of_step()
{
  step();
}

// the speed for the next step from this step's force; no force yet: approach at vmax
void FixServoPlate::step()
{
  const double dt = update->dt;
  const double F = input->variable->compute_equal(force_index);
  if (F != 0.0) {
    bool saturated = false;
    error_now = target - servo.measure(F, dt);
    speed = servo.velocity(error_now, dt, saturated);
  } else {
    servo.integral = 0.0;
    servo.primed = false;
    error_now = target;
    speed = servo.vmax;
  }
  if (tol > 0.0) {
    if (F != 0.0 && std::fabs(servo.filtered - target) < tol * target) nconv_count++;
    else nconv_count = 0;
  }
}

double FixServoPlate::compute_scalar()
{
  return speed;
}

double FixServoPlate::compute_vector(int n)
{
  if (n == 0) return speed;
  if (n == 1) return servo.filtered;
  if (n == 2) return (tol > 0.0 && nconv_count >= nconv) ? 1.0 : 0.0;
  return error_now;
}

int FixServoPlate::modify_param(int narg, char **arg)
{
  return parse(0, narg, arg, false);
}

void FixServoPlate::write_restart(FILE *fp)
{
  double list[4] = {servo.integral, servo.filtered, servo.primed ? 1.0 : 0.0, speed};
  if (comm->me == 0) {
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 4, fp);
  }
}

void FixServoPlate::restart(char *buf)
{
  double *list = (double *) buf;
  servo.integral = list[0];
  servo.filtered = list[1];
  servo.primed = list[2] != 0.0;
  speed = list[3];
}
