/* T-BAGS DEM toolkit: registration of the tbags plugin's styles (registration only). */

#include "lammpsplugin.h"
#include "version.h"

#include "bond_bpm_yarn.h"
#include "bond_yarn.h"
#include "fix_bond_history_tbags.h"
#include "fix_neigh_history_tbags.h"
#include "fix_table_time.h"
#include "fix_wall_gran_servo.h"
#include "pair_gran_hertz_rolling.h"

#ifndef TBAGS_VERSION
#define TBAGS_VERSION "0.2.0"
#endif

using namespace LAMMPS_NS;

static Pair *pair_gran_hertz_rolling_creator(LAMMPS *lmp)
{
  return new PairGranHertzRolling(lmp);
}

static Fix *fix_wall_gran_servo_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixWallGranServo(lmp, argc, argv);
}

static Fix *fix_table_time_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixTableTime(lmp, argc, argv);
}

static Fix *fix_neigh_history_tbags_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixNeighHistoryTbags(lmp, argc, argv);
}

static Fix *fix_bond_history_tbags_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixBondHistoryTbags(lmp, argc, argv);
}

static Bond *bond_bpm_yarn_creator(LAMMPS *lmp)
{
  return new BondBPMYarn(lmp);
}

static Bond *bond_yarn_creator(LAMMPS *lmp)
{
  return new BondYarn(lmp);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;

  plugin.version = LAMMPS_VERSION;
  plugin.style = "pair";
  plugin.name = "gran/hertz/rolling";
  plugin.info = "tbags " TBAGS_VERSION ": Hertz-Mindlin + restitution damping + rolling resistance";
  plugin.author = "T-BAGS DEM toolkit developers";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_gran_hertz_rolling_creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "wall/gran/servo";
  plugin.info = "tbags " TBAGS_VERSION ": rigid plate with force servo, gran/hertz/rolling contact law";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_wall_gran_servo_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "table/time";
  plugin.info = "tbags " TBAGS_VERSION ": a value tabulated against time (a displacement history)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_table_time_creator;
  (*register_plugin)(&plugin, lmp);

  // internal: the contact history store that pair gran/hertz/rolling creates
  plugin.name = "NEIGH_HISTORY/TBAGS";
  plugin.info = "tbags " TBAGS_VERSION ": contact history of gran/hertz/rolling (internal)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_neigh_history_tbags_creator;
  (*register_plugin)(&plugin, lmp);

  // internal: the bond history store that bond_style bpm/yarn creates
  plugin.name = "BOND_HISTORY/TBAGS";
  plugin.info = "tbags " TBAGS_VERSION ": bond history of bpm/yarn, kept across checkpoints (internal)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_bond_history_tbags_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "bond";
  plugin.name = "bpm/yarn";
  plugin.info = "tbags " TBAGS_VERSION ": tension-only nonlinear yarn bond, bending, twisting, breaking";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &bond_bpm_yarn_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "yarn";
  plugin.info = "tbags " TBAGS_VERSION ": tension-only nonlinear yarn bond (axial) for any atom style";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &bond_yarn_creator;
  (*register_plugin)(&plugin, lmp);
}
