"""The shear presets as data.

A preset is a bag (nx x ny x nz particles on the 5 mm lattice of inputs/in.bag), filled once
(inputs/in.fill), and one or more runs from that fill (inputs/in.shear or in.cyclic, each in a
subfolder, or in the fill's own folder), side by side or one after the other; then the
post-processing and the checks. Every run gets the bag's size; the user's -var values override
the preset's. shear.py runs them.
"""
from dataclasses import dataclass, field, replace

LOADS = (5500, 3730, 1960)    # the paper's three vertical loads (N on its 395 x 395 mm bag)
# runs of one fill at several loads share their compression up to this fraction of the smallest
# load's F_v (inputs/between_plates.lmp: -var compress_to, compress_from; below 0.98 every load's
# servo still runs at its speed limit, so the part is the same for all)
COMPRESS_SHARED = 0.9
DEMO_BAG = dict(nx=21, ny=21, nz=7)
# the presets that reproduce the paper run the fabric that reproduces its findings best (the
# evidence table in results/README.md); the design presets run both (DESIGN_FABRICS)
PAPER_FABRIC = {"fabric": "fabric solid (the paper's solid-bond cage, which reproduces its findings best; "
                          "-var fabric woven for a woven bag that carries no compression: ./tbags fabric)"}
DESIGN_FABRICS = ("solid", "woven")
# the paper's plan-to-height ratio: inner 130 x 130 x 25 mm (5.2) against 395 x 395 x 75 mm (5.27);
# 5 mm of shear is the paper's 20 % average shear strain
TRENDS_BAG = dict(nx=28, ny=28, nz=7)
PAPER_BAG = dict(nx=81, ny=81, nz=17)
# the rate study: the paper shears its 75 mm of sand at 4 mm/s; at the same stress the trends
# bag's 25 mm has the paper's inertial number (I = (v/H) d sqrt(rho/p)) at 4 x 25/75 mm/s, if its
# sand carries the same share of F_v (the load path measures it per run); RATE_MULTIPLES of it
PAPER_SPEED = 0.004
RATE_SPEED = PAPER_SPEED * (TRENDS_BAG["nz"] - 2) / (PAPER_BAG["nz"] - 2)
RATE_MULTIPLES = (1, 2, 4, 8)
# the protocol study: the top plate's speed limit while compressing (between_plates.lmp's
# vmax_compress, 0.02 m/s by default), at the highest load (the longest compression)
PROTOCOL_VMAX = (0.02, 0.05, 0.1, 0.2)


@dataclass(frozen=True)
class Run:
    folder: str          # under the preset's output folder; "" = the fill's own folder
    deck: str            # inputs/in.<deck>
    variables: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Preset:
    name: str
    folder: str                      # runs/<folder> unless --out
    bag: dict
    runs: tuple
    side_by_side: bool               # the runs at once, the ranks shared among them
    post: str                        # "figures" (S-u, shape, network, ParaView), "cyclic", "stack"
    check: str = ""                  # "trends", "speed" (tbagspost/check_trends.py), "rate", "protocol" (tbagspost/)
    defaults_said: dict = field(default_factory=dict)    # variable -> line printed when it is the preset's
    realizations: bool = True        # --realizations offered (not for runs of hours or days)
    estimate: bool = False           # measures a short stretch first and projects the time
    fabrics: tuple = ()              # run once per fabric (FABRIC/ subfolders) and compared, unless -var fabric
    help: str = ""
    # the runs whose compression is shared (shear.shared_compression) when --loads runs some of them
    compress_runs: tuple = ()

    def only(self, folders):
        """The preset with only the runs in folders (./tbags shear --loads), their compression
        still shared with all of its runs."""
        return replace(self, runs=tuple(r for r in self.runs if r.folder in folders),
                       compress_runs=self.compress_runs or self.runs)


def per_load(deck, **variables):
    return tuple(Run("F%d" % f, deck, dict(variables, Fpaper=f)) for f in LOADS)


PRESETS = {p.name: p for p in (
    Preset("demo", "shear-demo", DEMO_BAG,
           (Run("", "shear", dict(v=0.015, ufinal=0.005)),), False, "figures", defaults_said=PAPER_FABRIC,
           help="the main job: 21 x 21 x 7 bag (105 x 105 x 35 mm), the vertical stress of the "
                "paper's 5.5 kN load (F_v scaled by the inner plan area: 318 N), sheared at 15 mm/s to u = 5 mm (inertial number 8e-4 < "
                "1e-3); 2-3 minutes on 2 cores (about 9 on a bare machine: packages and the first "
                "LAMMPS build). -> runs/shear-demo/"),
    Preset("trends", "trends", TRENDS_BAG, per_load("shear", v=0.01, ufinal=0.005), True, "figures",
           check="trends", defaults_said=PAPER_FABRIC,
           help="28 x 28 x 7 bag, the paper's plan-to-height ratio (inner 130 x 130 x 25 mm, 5.2; the "
                "paper's 395 x 395 x 75 mm, 5.27), at the three loads (5.50, 3.73, 1.96 kN scaled by "
                "plan area; side by side), 10 mm/s to 5 mm, the paper's 20 % shear strain (inertial "
                "number 9e-4 at 1.96 kN), then tbagspost/check_trends.py asserts the paper's findings; "
                "with --realizations N in every realization. -> runs/trends/"),
    Preset("quasistatic", "quasistatic", TRENDS_BAG,
           tuple(Run("v%g" % v, "shear", dict(Fpaper=1960, v=v, ufinal=0.005)) for v in (0.01, 0.005)),
           True, "figures", check="speed", defaults_said=PAPER_FABRIC,
           help="the trends bag at 1.96 kN (its highest inertial number) at 10 and 5 mm/s to 5 mm: the "
                "S-u curves must agree (the speed does not drive the result). -> runs/quasistatic/"),
    Preset("rate", "rate", TRENDS_BAG,
           tuple(Run("I%d" % m, "shear", dict(Fpaper=1960, v=RATE_SPEED * m, ufinal=0.005)) for m in RATE_MULTIPLES),
           True, "figures", check="rate", defaults_said=PAPER_FABRIC,
           help="the rate study of the paper run: the trends bag at 1.96 kN (the highest inertial number) "
                "sheared to 5 mm at 1, 2, 4 and 8 times the paper's inertial number (1.33, 2.67, 5.33, "
                "10.7 mm/s; the paper's 4 mm/s on its 75 mm of sand is 1.33 mm/s on 25 mm), side by side; "
                "with --realizations 3 (about 3 h on 2 cores: 54 min a fill, bound by the slowest speed's 2.5 million steps) tbagspost/rate.py compares each speed "
                "with the slowest against the realizations' spread and names the fastest within it "
                "(rate.md). -> runs/rate/"),
    Preset("protocol", "protocol", TRENDS_BAG,
           tuple(Run("V%d" % round(1000 * vm), "shear", dict(Fpaper=5500, v=0.01, ufinal=0.001, vmax_compress=vm))
                 for vm in PROTOCOL_VMAX),
           True, "figures", check="protocol", defaults_said=PAPER_FABRIC,
           help="the compression's protocol: the trends bag at 5.50 kN (the longest compression) "
                "compressed with the top plate's speed limit at 20 (the decks' default), 50, 100 and "
                "200 mm/s, side by side, each held at F_v and sheared to 1 mm at 10 mm/s; with "
                "--realizations 3 tbagspost/protocol.py compares each with the slowest (w at F_v, paired "
                "by fill, also as a void ratio; F_v; S-u and w-u) against the fills' spread and names the "
                "fastest within it (protocol.md). The fill's settling: the same with -var nsettle 10000 "
                "-var settle_chunk 5000 --loads V20 --out runs/protocol-fill, then "
                "python3 -m tbagspost.protocol runs/protocol --fill runs/protocol-fill. -> runs/protocol/"),
    Preset("cyclic", "cyclic", DEMO_BAG, per_load("cyclic"), True, "cyclic", realizations=False,
           fabrics=DESIGN_FABRICS,
           help="the demo bag at the three loads' stresses (side by side), cycled with F_v held: "
                "amplitudes 0.25 0.5 1 2 3 5 mm, 3 sine cycles each, every amplitude at the same "
                "15 mm/s peak plate speed (in.cyclic: -var amps \"0.25 1 5\" -var cycles N -var wave "
                "triangle -var vpeak V or -var freq F); then the loops, K_eq/K_0 and h_eq curves, "
                "Ramberg-Osgood fit and report.md (tbagspost/cyclic.py); with the fabrics solid and woven "
                "(-var fabric F for one), compared in fabrics.md. Hours on 2 cores; each load "
                "checkpoints after every amplitude (--resume continues there). -> runs/cyclic/{solid,woven}"),
    Preset("stack", "stack", DEMO_BAG,
           (Run("single", "cyclic", dict(Fpaper=3730)),
            Run("stack", "cyclic", dict(Fpaper=3730, bags=2, film_mu=0.1))), True, "stack",
           defaults_said={"film_mu": "film friction 0.1 (a geotextile on UHMWPE; -var film_mu MU for yours)"},
           realizations=False, fabrics=DESIGN_FABRICS,
           help="the T-BAGS system: two demo bags (one fill) stacked with a polymer film sheet between "
                "them (fix wall/gran/servo film: 0.5 mm, free to move; its friction against the bags "
                "-var film_mu, 0.1 unless given: a geotextile on UHMWPE, doc/fix_wall_gran_servo.rst; "
                "-var film_mu_below 1e10 fixes it to the lower bag), at 3.73 kN's stress with the "
                "cyclic protocol, and one bag of the same fill beside it; then the cyclic analysis of "
                "both and the split of the plate's displacement into bag shear and film slip "
                "(tbagspost/stack.py); with the fabrics solid and woven (-var fabric F for one), compared "
                "in fabrics.md. Hours on 2 cores; checkpoints after every amplitude (--resume). "
                "-> runs/stack/{solid,woven}/{stack,single,figures}"),
    Preset("paper", "paper", PAPER_BAG, per_load("shear", v=0.004, ufinal=0.015), False, "figures",
           realizations=False, estimate=True, defaults_said=PAPER_FABRIC,
           help="the full 81 x 81 x 17 bag (17,922 particles, 35,840 bonds, 97,130 grains) at the three "
                "loads, 4 mm/s (the paper's speed, kept by the rate study: results/rate/) to u = 15 mm: about 7 h a load on 2 cores (2.5 million steps; --loads F1960 runs one load per "
                "job and makes no estimate). Without --loads it first "
                "makes its bag and fill, compresses and shears them to a checkpoint, times a short "
                "stretch from it at 1, 2 and N ranks, counts LAMMPS's decomposition at 4-64 ranks "
                "and prints the projected time and the scaling model (about an hour on 2 cores, "
                "once: a second call reuses the fill and checkpoint); `paper --estimate` stops "
                "there. Each load checkpoints every 1 mm of u: `paper --resume` continues an "
                "interrupted run. -> runs/paper/"),
)}

# the paper preset's estimate, on the paper's own bag and fill: compression and shearing to
# u = 20 um (a checkpoint), then 20 um more (3,333 steps at 4 mm/s and 1.5 us) timed at 1, 2 and N
# ranks resumed from it; CSV rows every 10 um so that both stretches are whole rows
ESTIMATE = dict(v=0.004, du_csv=1e-5, du_dump=2e-5, u_state=2e-5, u_timed=2e-5)
# ranks whose domain decomposition of the paper bag the scaling model counts (a few steps each)
DECOMPOSITIONS = (4, 8, 16, 32, 64)
