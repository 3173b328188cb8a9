/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   bond_style bpm/yarn: tension-only nonlinear yarn bond with bending, twisting and breaking,
   on LAMMPS BPM's BondBPM base. The physics is law/yarn_law.h, run over batches of bonds by
   law/yarn_chain.h.
------------------------------------------------------------------------- */

#ifndef LMP_BOND_BPM_YARN_H
#define LMP_BOND_BPM_YARN_H

#include "atom.h"
#include "bond_bpm.h"
#include "law/yarn_chain.h"
#include "update.h"
#include "yarn_table.h"

#include <memory>
#include <vector>

namespace LAMMPS_NS {

class BondBPMYarn : public BondBPM {
 public:
  BondBPMYarn(class LAMMPS *);
  ~BondBPMYarn() override;
  void compute(int, int) override;
  void coeff(int, char **) override;
  void init_style() override;
  void settings(int, char **) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_data(FILE *) override;
  double single(int, double, int, int, double &) override;

 protected:
  std::vector<YarnCoeff> coeffs;    // per bond type
  int warned_integrator = 0;
  // the batch of bonds run through the law together, and where each lane's bond is
  std::unique_ptr<tbags::yarn::Batch> batch;
  int lane_bond[tbags::yarn::Batch::N], lane_i[tbags::yarn::Batch::N], lane_j[tbags::yarn::Batch::N];
  bool kernel_baseline = false;    // keyword kernel baseline: never the AVX2 build
  int kernel_avx2 = -1;            // the build init_style() chose (1: AVX2)
  void flush(int nb, int btype);
  void allocate();
  void store_data();
  bool bond_history(int i, int j, double *hist);
  void create_history_store();
  // the law's view of the bond i-j (ends ordered by the caller)
  tbags::yarn::Bond bond_state(int i, int j) const
  {
    tbags::yarn::Bond b;
    b.xi = atom->x[i];
    b.xj = atom->x[j];
    b.vi = atom->v[i];
    b.vj = atom->v[j];
    b.wi = atom->omega[i];
    b.wj = atom->omega[j];
    b.dt = update->dt;
    return b;
  }
};

}    // namespace LAMMPS_NS

#endif
