/* T-BAGS DEM toolkit: the contact law of law/contact_law.h as a LIGGGHTS contact model,
     pair_style gran model tbags [rollingCDT on] [limitForce on]
     fix wall/gran model tbags mesh|primitive ...
   LIGGGHTS splits a contact into normal, tangential and rolling models; this "normal model"
   runs the whole law (Hertz, restitution damping, Mindlin spring with Coulomb cap, EPSD or CDT
   rolling) through law/contact_chain.h, the same code as pair_style gran/hertz/rolling and fix
   wall/gran/servo in LAMMPS, so the tangential and rolling slots stay off. Materials from
   LIGGGHTS's own properties: youngsModulus, poissonsRatio (per type), coefficientRestitution,
   coefficientFriction, coefficientRollingFriction (per type pair); rolling EPSD unless
   rollingCDT on, none for a pair whose mu_r is 0. History: 6 values per contact (tangential and
   rolling displacement), both flipping sign with the pair's order, zeroed at the step the
   contact opens, as in LAMMPS: LIGGGHTS tells a model that a pair has parted (surfacesClose)
   only within its contact distance factor, which this model raises to 1.01 (a pair would have
   to part by 1 % of r_i + r_j in one step to skip it).
   build-liggghts.sh copies this file and law/ into the LIGGGHTS tree (no plugin loader there).
*/
#ifdef NORMAL_MODEL
NORMAL_MODEL(TBAGS,tbags,20)
#else
#ifndef NORMAL_MODEL_TBAGS_H_
#define NORMAL_MODEL_TBAGS_H_
#include "contact_models.h"
#include "normal_model_base.h"
#include "global_properties.h"
#include "force.h"
#include "neighbor.h"
#include "update.h"
#include "law/contact_chain.h"

#include <vector>

namespace LIGGGHTS {
namespace ContactModels
{
  template<>
  class NormalModel<TBAGS> : public NormalModelBase
  {
  public:
    NormalModel(LAMMPS * lmp, IContactHistorySetup * hsetup, class ContactModelBase * c) :
      NormalModelBase(lmp, hsetup, c), wall_(c && c->is_wall())
    {
      history_ = hsetup->add_history_value("tbags_tx", "1");
      hsetup->add_history_value("tbags_ty", "1");
      hsetup->add_history_value("tbags_tz", "1");
      hsetup->add_history_value("tbags_rx", "1");
      hsetup->add_history_value("tbags_ry", "1");
      hsetup->add_history_value("tbags_rz", "1");
    }

    void registerSettings(Settings & settings)
    {
      settings.registerOnOff("rollingCDT", cdt_, false);
      settings.registerOnOff("limitForce", limit_, false);
    }

    void postSettings(IContactHistorySetup *, ContactModelBase *) {}

    void connectToProperties(PropertyRegistry & registry)
    {
      if (force->nktv2p != 1.0)
        error->all(FLERR, "model tbags: needs units in which force = pressure x area (si, cgs, lj)");
      registry.registerProperty("Yeff", &MODEL_PARAMS::createYeff, "model tbags");
      registry.registerProperty("Geff", &MODEL_PARAMS::createGeff, "model tbags");
      registry.registerProperty("coeffRest", &MODEL_PARAMS::createCoeffRest, "model tbags");
      registry.registerProperty("coeffFrict", &MODEL_PARAMS::createCoeffFrict, "model tbags");
      registry.registerProperty("coeffRollFrict", &MODEL_PARAMS::createCoeffRollFrict, "model tbags");
      registry.connect("Yeff", Yeff_, "model tbags");
      registry.connect("Geff", Geff_, "model tbags");
      registry.connect("coeffRest", rest_, "model tbags");
      registry.connect("coeffFrict", mu_, "model tbags");
      registry.connect("coeffRollFrict", mur_, "model tbags");
      ntypes_ = registry.max_type();
      params_.clear();    // rebuilt from the properties at the first contact of the run
      neighbor->register_contact_dist_factor(1.01);    // surfacesClose() as a contact opens
    }

    double stressStrainExponent() { return 1.5; }

    void surfacesIntersect(SurfacesIntersectData & sidata, ForceData & i_forces, ForceData & j_forces)
    {
      namespace law = tbags::contact;    // qualified: LIGGGHTS has names of its own alike
      if (sidata.contact_flags) *sidata.contact_flags |= CONTACT_NORMAL_MODEL;
      if (params_.empty()) build_params();
      const law::Params & p = params_[sidata.itype * (ntypes_ + 1) + sidata.jtype];
      static const double zero[3] = {0.0, 0.0, 0.0};
      law::Contact c;
      c.dx = sidata.delta;    // x_i - x_j; a wall: from its contact point to x_i
      c.radi = sidata.radi;
      c.radj = wall_ ? 0.0 : sidata.radj;
      c.reff = wall_ ? sidata.radi : sidata.radi * sidata.radj / (sidata.radi + sidata.radj);
      c.meff = sidata.meff;
      c.vi = sidata.v_i;
      c.vj = sidata.v_j;
      c.wi = sidata.omega_i;
      c.wj = wall_ ? zero : sidata.omega_j;
      c.wall = wall_;
      c.dt = update->dt;
      law::Result o;
      law::compute(p, c, &sidata.contact_history[history_], sidata.computeflag && sidata.shearupdate, o);
      sidata.Fn = o.fn;
      for (int k = 0; k < 3; k++) {
        i_forces.delta_F[k] += o.f[k];
        i_forces.delta_torque[k] += o.ti[k];
        if (!wall_) {
          j_forces.delta_F[k] -= o.f[k];
          j_forces.delta_torque[k] += o.tj[k];
        }
      }
    }

    // a pair (or a particle and a wall) just apart: the contact is over, its history goes
    void surfacesClose(SurfacesCloseData & scdata, ForceData &, ForceData &)
    {
      if (scdata.contact_flags) *scdata.contact_flags &= ~CONTACT_NORMAL_MODEL;
      if (!scdata.contact_history) return;
      for (int k = 0; k < 6; k++) scdata.contact_history[history_ + k] = 0.0;
    }
    void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) {}
    void endPass(SurfacesIntersectData &, ForceData &, ForceData &) {}

  private:
    // the law's constants per type pair, from LIGGGHTS's (already mixed) material matrices
    void build_params()
    {
      namespace law = tbags::contact;
      const int n = ntypes_ + 1;
      params_.assign(n * n, law::Params());
      for (int i = 1; i < n; i++)
        for (int j = 1; j < n; j++) {
          if (mur_[i][j] < 0.0 || mu_[i][j] < 0.0)
            error->all(FLERR, "model tbags: coefficientFriction and coefficientRollingFriction must be >= 0");
          // (qualified: LIGGGHTS's ContactModels has rolling-model ids of the same names)
          params_[i * n + j] = law::make_params(Yeff_[i][j], Geff_[i][j], rest_[i][j], mu_[i][j],
                                                mur_[i][j], cdt_ ? law::ROLLING_CDT : law::ROLLING_EPSD,
                                                limit_);
        }
    }

    bool wall_;
    bool cdt_ = false, limit_ = false;
    int history_ = 0, ntypes_ = 0;
    double ** Yeff_ = nullptr, ** Geff_ = nullptr, ** rest_ = nullptr, ** mu_ = nullptr,
           ** mur_ = nullptr;
    std::vector<tbags::contact::Params> params_;
  };
}
}
#endif
#endif
