#!/usr/bin/python3
"""Writes the synthetic sample of vispmorph-bench output used by the ctests of the bench's Python tools:
runs.csv, curves.csv and timings.csv in vispmorph-bench's format, into the folder given (default: this
script's folder). The numbers are made up (a fixed seed), not measured: they only exercise the plots, with every
set and controller, failures of every kind, empty path_ratio and final_tag_* fields, a controller absent from a
set (pbvs on deformable), a set where every run of a controller failed (ibvs-current on planar-hard) and a run
without curve."""

import math
import os
import random
import sys

SETS = ["planar", "planar-hard", "6dof", "calib", "noise", "occlusion", "deformable"]
CONTROLLERS = ["morph", "morph-vpservo", "ibvs-current", "ibvs-desired", "ibvs-mean", "pbvs", "moments"]
FAILURES = ["out-of-view", "feature-lost", "joint-limit", "budget", "final-error", "diverged", "recognition",
            "unreachable"]
RUN_HEADER = ("set,robot,controller,scenario,seed,object,start_rotation_deg,start_translation_mm,start_tilt_deg,"
              "start_depth_change,success,failure,iterations,converged_iteration,path_length_m,straight_line_m,"
              "path_ratio,final_t_mm,final_r_deg,final_tag_t_mm,final_tag_r_deg,recognized,recognition_correct,"
              "faults,holds,replans,rerecognitions,max_speed_mps,max_rotation_speed_degps,goal,setup,converged,"
              "false_converged,truth,tag_size_mm,taught_tag_t_mm,taught_tag_r_deg,final_overlap_t_mm,"
              "final_overlap_r_deg,symmetry,unobservable,verification")
TIMINGS_HEADER = ("set,robot,controller,scenario,object,yardstick_ms,measure_ms,control_ms,max_control_ms,run_cpu_s,"
                  "period_ms,period_measure_ms")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    rng = random.Random(4)
    runs, curves = [RUN_HEADER], ["set,robot,controller,scenario,iteration,t_mm,r_deg"]
    timings = [TIMINGS_HEADER]
    for s in SETS:
        for c in CONTROLLERS:
            if s == "deformable" and c == "pbvs":
                continue  # a controller with no row in a set
            for k in range(1 if s not in ("planar", "planar-hard") else 2):
                scenario = "%s-%03d" % (s, k)
                rot = rng.uniform(150, 180) if s == "planar-hard" else rng.uniform(-180, 180)
                trans = rng.uniform(0, 80)
                p_ok = 0.9 if c.startswith("morph") else 0.6 - 0.3 * (abs(rot) > 120 and c.startswith("ibvs"))
                ok = rng.random() < p_ok and not (s == "planar-hard" and c == "ibvs-current")
                failure = "none" if ok else FAILURES[rng.randrange(len(FAILURES))]
                iters = rng.randint(15, 40) if ok else rng.randint(5, 60)
                straight = 0.0 if (s == "calib" and c in ("pbvs", "morph")) else trans / 1000.0
                path = straight * rng.uniform(1.0, 1.3 if c.startswith("morph") else 2.5) + 0.001
                ratio = "%.4f" % (path / straight) if straight > 0 else ""
                ft, fr = (rng.uniform(0.05, 0.9), rng.uniform(0.01, 0.45)) if ok else (rng.uniform(1, 200),
                                                                                      rng.uniform(0.5, 90))
                tag = ("%.3f" % (ft + rng.uniform(0, 0.3)), "%.3f" % (fr + rng.uniform(0, 0.05)))
                if rng.random() < 0.15:
                    tag = ("", "")  # tag not detected
                robot = "viper850" if s == "6dof" else "free"
                fields = [
                    s, robot, c, scenario, 1000 + k, "pliers", "%.2f" % rot,
                    "%.1f" % trans, "%.1f" % (rng.uniform(0, 30) if s == "6dof" else 0.0),
                    "%.2f" % (rng.uniform(-0.4, 0.4) if s == "6dof" else 0.0), int(ok), failure, iters,
                    iters if ok else "", "%.4f" % path, "%.4f" % straight, ratio, "%.3f" % ft, "%.3f" % fr, tag[0],
                    tag[1], 1, int(rng.random() < 0.95)]
                measure, control = "%.2f" % rng.uniform(1, 6), "%.3f" % rng.uniform(0.01, 0.5)
                # A run that stopped as converged away from the goal is a false convergence.
                false_converged = int(failure == "final-error")
                fields += ["", 0, 0, 0, "", "", 0, "", int(ok or false_converged), false_converged, "rigid", 80, "",
                           "", "", "", 1, "", "verified" if ok or false_converged else ""]
                runs.append(",".join(str(v) for v in fields))
                period = float(measure) + float(control)
                timings.append(",".join(str(v) for v in [
                    s, robot, c, scenario, "pliers", 0.8, measure, control, control, "%.3g" % (0.01 * iters * period),
                    " ".join("%.4g" % (period * f) for f in (0.9, 1.0, 1.1)),
                    " ".join("%.4g" % (float(measure) * f) for f in (0.9, 1.0, 1.1))]))
                if s == "noise" and c == "moments":
                    continue  # a run without curve
                t0, r0 = max(trans, 1.0), max(abs(rot), 1.0)
                for i in range(iters + 1):
                    a = math.exp(-0.25 * i)
                    t = ft + (t0 - ft) * a if ok else t0 * (1 + 0.05 * i)
                    r = fr + (r0 - fr) * a if ok else r0 * (0.8 + 0.2 * a)
                    curves.append("%s,%s,%s,%s,%d,%.4f,%.4f" % (s, "viper850" if s == "6dof" else "free", c,
                                                                 scenario, i, t, r))
    with open(os.path.join(out, "runs.csv"), "w") as f:
        f.write("\n".join(runs) + "\n")
    with open(os.path.join(out, "curves.csv"), "w") as f:
        f.write("\n".join(curves) + "\n")
    with open(os.path.join(out, "timings.csv"), "w") as f:
        f.write("\n".join(timings) + "\n")


if __name__ == "__main__":
    main()
