/* T-BAGS DEM toolkit: yarn table reader and shared bond_coeff parsing (see yarn_table.h). */

#include "yarn_table.h"

#include "comm.h"
#include "error.h"
#include "platform.h"
#include "table_file_reader.h"
#include "tokenizer.h"
#include "utils.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

using namespace LAMMPS_NS;

void LAMMPS_NS::read_yarn_table(LAMMPS *lmp, const char *style, const std::string &file,
                                const std::string &keyword, tbags::yarn::Curve &curve,
                                bool &force_table)
{
  // rank 0 reads (LAMMPS file readers are rank-0 only) and broadcasts the curve or the error
  Error *error = lmp->error;
  MPI_Comm world = lmp->world;
  curve.eps.clear();
  curve.val.clear();
  int ftab = 0;
  std::string why;
  if (lmp->comm->me == 0) {
    try {
      if (!platform::file_is_readable(file))
        throw std::runtime_error("the file is missing or unreadable");
      TableFileReader reader(lmp, file, "bond");
      char *line = reader.find_section_start(keyword);
      if (!line) throw std::runtime_error("no section '" + keyword + "'");
      line = reader.next_line();
      ValueTokenizer head(line);
      int n = 0;
      while (head.has_next()) {
        const std::string w = head.next_string();
        if (w == "N") n = head.next_int();
        else if (w == "FORCE") ftab = 1;
        else throw std::runtime_error("unknown word '" + w + "' in the N line");
      }
      if (n < 2) throw std::runtime_error("the N line needs 'N n' with n >= 2");
      reader.skip_line();
      for (int i = 0; i < n; i++) {
        line = reader.next_line();
        if (!line) throw std::runtime_error("the table ends after " + std::to_string(i) + " lines");
        ValueTokenizer values(line);
        values.next_int();
        curve.eps.push_back(values.next_double());
        curve.val.push_back(values.next_double());
      }
    } catch (std::exception &e) {
      why = e.what();
    }
  }
  int len = (int) why.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, world);
  if (len > 0) {
    why.resize(len);
    MPI_Bcast(&why[0], len, MPI_CHAR, 0, world);
    error->all(FLERR, "{}: cannot read yarn table {} from {}: {}", style, keyword, file, why);
  }
  int n = (int) curve.eps.size();
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  MPI_Bcast(&ftab, 1, MPI_INT, 0, world);
  curve.eps.resize(n);
  curve.val.resize(n);
  MPI_Bcast(curve.eps.data(), n, MPI_DOUBLE, 0, world);
  MPI_Bcast(curve.val.data(), n, MPI_DOUBLE, 0, world);
  force_table = ftab != 0;
  const char *bad = tbags::yarn::check_curve(curve);
  if (*bad) error->all(FLERR, "{}: yarn table {} in {}: {}", style, keyword, file, bad);
}

void LAMMPS_NS::parse_yarn_coeff(LAMMPS *lmp, const char *style, int narg, char **arg,
                                 YarnCoeff &c, double *r0)
{
  const bool axial_only = r0 != nullptr;
  if (r0) *r0 = -1.0;
  Error *error = lmp->error;
  if (narg < 4 || strcmp(arg[1], "table") != 0)
    error->all(FLERR, "{}: write 'bond_coeff T table FILE KEYWORD diameter D{}'", style,
               axial_only ? " r0 R0" : " poisson NU");
  c.file = arg[2];
  c.keyword = arg[3];
  read_yarn_table(lmp, style, c.file, c.keyword, *c.curve, c.p.force_table);
  double E = -1.0, nu = -2.0, kappa = -1.0, brk = -1.0;
  c.p.d = -1.0;
  c.p.gn = c.p.gs = c.p.gr = 0.0;
  c.p.plastic = false;
  for (int iarg = 4; iarg < narg;) {
    const std::string kw = arg[iarg];
    auto need = [&](int n) {
      if (iarg + n >= narg) error->all(FLERR, "{}: keyword '{}' needs {} value(s)", style, kw, n);
    };
    auto num = [&](int k) { return utils::numeric(FLERR, arg[iarg + k], false, lmp); };
    if (kw == "diameter") {
      need(1);
      c.p.d = num(1);
      iarg += 2;
    } else if (kw == "break") {
      need(1);
      brk = num(1);
      iarg += 2;
    } else if (axial_only && kw == "r0") {
      need(1);
      *r0 = num(1);
      iarg += 2;
    } else if (axial_only && kw == "damping") {
      need(1);
      c.p.gn = num(1);
      if (c.p.gn < 0.0) error->all(FLERR, "{}: damping must be >= 0", style);
      iarg += 2;
    } else if (!axial_only && kw == "damping") {
      need(3);
      c.p.gn = num(1);
      c.p.gs = num(2);
      c.p.gr = num(3);
      if (c.p.gn < 0.0 || c.p.gs < 0.0 || c.p.gr < 0.0)
        error->all(FLERR, "{}: damping coefficients must be >= 0", style);
      iarg += 4;
    } else if (!axial_only && kw == "unload") {
      need(1);
      if (strcmp(arg[iarg + 1], "plastic") == 0) c.p.plastic = true;
      else if (strcmp(arg[iarg + 1], "elastic") == 0) c.p.plastic = false;
      else error->all(FLERR, "{}: unload must be elastic or plastic", style);
      iarg += 2;
    } else if (!axial_only && kw == "E") {
      need(1);
      E = num(1);
      iarg += 2;
    } else if (!axial_only && kw == "poisson") {
      need(1);
      nu = num(1);
      iarg += 2;
    } else if (!axial_only && kw == "shear") {
      need(1);
      kappa = num(1);
      if (kappa < 0.0)
        error->all(FLERR, "{}: shear coefficient must be >= 0 (0: no shear spring), got {}", style, kappa);
      iarg += 2;
    } else {
      error->all(FLERR, "{}: unknown bond_coeff keyword '{}'", style, kw);
    }
  }
  if (c.p.d <= 0.0)
    error->all(FLERR, "{}: bond_coeff needs 'diameter D' with D > 0 (m)", style);
  if (axial_only && *r0 <= 0.0)
    error->all(FLERR, "{}: bond_coeff needs 'r0 R0' with R0 > 0 (m), the unstretched length", style);
  const double last = c.curve->eps.back();
  if (brk < 0.0) brk = last;
  if (brk <= 0.0 || brk > last)
    error->all(FLERR, "{}: break strain {} must be in (0, {}] (the table's last strain)", style, brk, last);
  c.p.eps_break = brk;
  if (!axial_only) {
    if (nu <= -1.0 || nu >= 0.5)
      error->all(FLERR, "{}: bond_coeff needs 'poisson NU' with -1 < NU < 0.5 (G = E/2(1+NU))", style);
    const double E0 = c.p.force_table ? c.curve->slope0() / c.p.area() : c.curve->slope0();
    if (E < 0.0) E = E0;
    if (E <= 0.0) error->all(FLERR, "{}: E must be > 0 Pa", style);
    if (kappa < 0.0) kappa = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);    // circular section
    c.p.E = E;
    c.p.nu = nu;
    c.p.kappa = kappa;
  }
  c.set = true;
}

void LAMMPS_NS::write_yarn_coeff(FILE *fp, const YarnCoeff &c)
{
  const int set = c.set ? 1 : 0;
  fwrite(&set, sizeof(int), 1, fp);
  if (!set) return;
  const int n = (int) c.curve->eps.size();
  const int lf = (int) c.file.size() + 1, lk = (int) c.keyword.size() + 1;
  fwrite(&n, sizeof(int), 1, fp);
  fwrite(c.curve->eps.data(), sizeof(double), n, fp);
  fwrite(c.curve->val.data(), sizeof(double), n, fp);
  double v[10] = {c.p.d, c.p.E, c.p.nu, c.p.kappa, c.p.eps_break, c.p.gn, c.p.gs, c.p.gr,
                  c.p.plastic ? 1.0 : 0.0, c.p.force_table ? 1.0 : 0.0};
  fwrite(v, sizeof(double), 10, fp);
  fwrite(&lf, sizeof(int), 1, fp);
  fwrite(c.file.c_str(), 1, lf, fp);
  fwrite(&lk, sizeof(int), 1, fp);
  fwrite(c.keyword.c_str(), 1, lk, fp);
}

void LAMMPS_NS::read_yarn_coeff(LAMMPS *lmp, FILE *fp, YarnCoeff &c)
{
  Error *error = lmp->error;
  const int me = lmp->comm->me;
  MPI_Comm world = lmp->world;
  int set = 0, n = 0;
  if (me == 0) utils::sfread(FLERR, &set, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&set, 1, MPI_INT, 0, world);
  c.set = set != 0;
  if (!set) return;
  if (me == 0) utils::sfread(FLERR, &n, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  c.curve->eps.resize(n);
  c.curve->val.resize(n);
  double v[10];
  if (me == 0) {
    utils::sfread(FLERR, c.curve->eps.data(), sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, c.curve->val.data(), sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, v, sizeof(double), 10, fp, nullptr, error);
  }
  MPI_Bcast(c.curve->eps.data(), n, MPI_DOUBLE, 0, world);
  MPI_Bcast(c.curve->val.data(), n, MPI_DOUBLE, 0, world);
  MPI_Bcast(v, 10, MPI_DOUBLE, 0, world);
  c.p.d = v[0];
  c.p.E = v[1];
  c.p.nu = v[2];
  c.p.kappa = v[3];
  c.p.eps_break = v[4];
  c.p.gn = v[5];
  c.p.gs = v[6];
  c.p.gr = v[7];
  c.p.plastic = v[8] != 0.0;
  c.p.force_table = v[9] != 0.0;
  for (std::string *s : {&c.file, &c.keyword}) {
    int len = 0;
    if (me == 0) utils::sfread(FLERR, &len, sizeof(int), 1, fp, nullptr, error);
    MPI_Bcast(&len, 1, MPI_INT, 0, world);
    std::vector<char> buf(len);
    if (me == 0) utils::sfread(FLERR, buf.data(), 1, len, fp, nullptr, error);
    MPI_Bcast(buf.data(), len, MPI_CHAR, 0, world);
    *s = buf.data();
  }
}
