#!/usr/bin/env python3
"""The cli tests of sss-render: sss_render_tests.py SSS_RENDER SOURCE_DIR CASE (one case per CTest/Meson test).

broken         every scene in tests/cli/broken/ fails with exit status 1, one error line holding its expected
               fragment (file, line:column or key path, what is wrong), and writes no file nor leaves the output
               directory it made; --dry-run, which builds the scene and the simulator, finds the same error
roundtrip      --dry-run output, read again, prints the same resolved scene
outputs        a valid scene writes exactly the files it asks for (and a changed stem / npy = false changes them);
               a planar-array scene, a trajectory scene and a double scene render, --pings beyond render.pings
               is an error; an output that cannot be written is named, and nothing is written
interrupt      SIGINT or SIGTERM during the render: exit status 130 or 143, one line, no file left (not even a
               temporary one)
progress_tty   on a pseudo-terminal the progress is a redrawn bar with pings done, pings/s and ETA
progress_plain without a terminal the progress is plain lines, the last one with every ping done
"""
import os, pty, re, resource, signal, struct, subprocess, sys, tempfile, time

exe, src, case = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
cli = os.path.join(src, "tests", "cli")
small = os.path.join(cli, "scenes", "small.toml")
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(args, cwd=None):
    return subprocess.run([exe] + args, capture_output=True, text=True, cwd=cwd, timeout=120)


def files_in(d):
    return sorted(os.listdir(d)) if os.path.isdir(d) else []


if case == "broken":
    broken = os.path.join(cli, "broken")
    table = [l.split("\t") for l in open(os.path.join(broken, "expected.txt")).read().splitlines() if l and not l.startswith("#")]
    on_disk = sorted(f for f in os.listdir(broken) if f.endswith(".toml"))
    check(sorted(n for n, _ in table) == on_disk, "expected.txt lists every broken scene once")
    check(len(table) >= 25, "at least 25 broken scenes")
    for name, fragment in table:
        with tempfile.TemporaryDirectory() as out:
            r = run([name, "-o", os.path.join(out, "o")], cwd=broken)
            errors = [l for l in r.stderr.splitlines() if "warning:" not in l]
            check(r.returncode == 1, f"{name}: exit status 1 (got {r.returncode})")
            check(len(errors) == 1, f"{name}: one error line (got {errors})")
            check(bool(errors) and fragment in errors[0], f"{name}: message holds '{fragment}' (got {errors})")
            check(not os.path.exists(os.path.join(out, "o")), f"{name}: no file written, no directory left")
            r = run([name, "--dry-run"], cwd=broken)
            errors = [l for l in r.stderr.splitlines() if "warning:" not in l]
            check(r.returncode == 1 and bool(errors) and fragment in errors[0],
                  f"{name}: --dry-run finds the same error ({r.returncode}, {errors})")

elif case == "roundtrip":
    with tempfile.TemporaryDirectory() as d:
        scenes = [small] + [os.path.join(cli, "scenes", n) for n in ["primitives.toml", "layered.toml", "planar.toml", "trajectory.toml",
                                                                      "georeferenced.toml"]]
        for scene in scenes + [os.path.join(src, "examples", "scenes", "demo.toml")]:
            # From the scene's directory: a relative file key (trajectory.toml's turn.csv) is read from there.
            first = run([scene, "--dry-run"], cwd=os.path.dirname(scene))
            check(first.returncode == 0, f"{scene}: --dry-run succeeds ({first.stderr})")
            resolved = os.path.join(d, "resolved.toml")
            open(resolved, "w").write(first.stdout)
            second = run([resolved, "--dry-run"], cwd=os.path.dirname(scene))
            check(second.returncode == 0 and second.stdout == first.stdout, f"{scene}: the resolved scene reads back to itself")
            # From elsewhere: a relative file key leads from the scene file's directory, not the working directory.
            elsewhere = run([scene, "--dry-run"], cwd=d)
            check(elsewhere.returncode == 0 and elsewhere.stdout == first.stdout,
                  f"{scene}: the same resolved scene from another working directory ({elsewhere.stderr})")
            for key in ["threads =", "cell_m =", "absorption_db_per_km =", "pulse_shape =", "png_dynamic_range_db =", "precision ="]:
                check(key in first.stdout, f"{scene}: the resolved scene fills in {key}")
            # The regions' boundary keys where regions meet, and only there (a flat seabed, or one of a single region,
            # refuses them); the seed wherever there are regions.
            regions = first.stdout.count("[[seabed.region]]")
            seabed = first.stdout[first.stdout.find("[seabed]\n"):]
            seabed = seabed[:seabed.find("\n[", 1) + 1]
            check(("\nblend_m =" in seabed) == (regions > 1) and ("\npartition_seed =" in seabed) == (regions > 1)
                  and ("\nseed =" in seabed) == (regions > 0),
                  f"{scene}: the resolved scene has seed where it has regions, blend_m and partition_seed where they meet")
            want = 'precision = "double"' if scene.endswith("georeferenced.toml") else 'precision = "float"'
            check(want in first.stdout, f"{scene}: the resolved scene keeps {want}")
            check(files_in(d) == ["resolved.toml"], "--dry-run writes nothing")

elif case == "outputs":
    with tempfile.TemporaryDirectory() as d:
        r = run([small, "-o", os.path.join(d, "a")])
        check(r.returncode == 0, f"render succeeds ({r.stderr})")
        check(files_in(os.path.join(d, "a")) == ["small.json", "small.npy", "small.png"], f"exactly the asked files ({files_in(os.path.join(d, 'a'))})")
        png = open(os.path.join(d, "a", "small.png"), "rb").read()
        check(png[:8] == b"\x89PNG\r\n\x1a\n", "the PNG is a PNG")
        npy = open(os.path.join(d, "a", "small.npy"), "rb").read()
        check(npy[:6] == b"\x93NUMPY" and b"(24, " in npy[:128], "the .npy holds 24 pings")
        everything = open(small).read().replace("npy = true", "npy = true\nxtf = true\ncoco = true\nyolo = true\nlabel_images = true")
        scene3 = os.path.join(d, "every.toml")
        open(scene3, "w").write(everything)
        r = run([scene3, "-o", os.path.join(d, "e")])
        want = ["classes.txt", "small.json", "small.npy", "small.png", "small.txt", "small.xtf", "small_coco.json",
                "small_labels_class.png", "small_labels_instance.png", "small_labels_legend.json"]
        check(r.returncode == 0 and files_in(os.path.join(d, "e")) == want, f"every product asked, and nothing else ({files_in(os.path.join(d, 'e'))}, {r.stderr})")
        if r.returncode == 0:  # the record is not TVG'd: the XTF's ProcessingFlags say so, and with TVG they say that
            xtf = open(os.path.join(d, "e", "small.xtf"), "rb").read()
            check(struct.unpack_from("<H", xtf, 1024 + 256 + 24)[0] == 0, "without TVG, ProcessingFlags is 0")
            open(os.path.join(d, "tvg.toml"), "w").write(everything + "\n[receiver]\ntvg = true\n")
            r = run([os.path.join(d, "tvg.toml"), "-o", os.path.join(d, "tvg")])
            xtf = open(os.path.join(d, "tvg", "small.xtf"), "rb").read() if r.returncode == 0 else b""
            check(len(xtf) > 1024 + 256 + 26 and struct.unpack_from("<H", xtf, 1024 + 256 + 24)[0] == 4,
                  f"with receiver.tvg the XTF's ProcessingFlags is 4, TVG applied ({r.stderr})")
        # An output that cannot be written (here a file size limit of 40,000 bytes: the 17 kB PNG passes, the
        # 128 kB .npy does not) is named by its own name, not the scene's nor a temporary one; nothing is written,
        # and an earlier run's files stay whole.
        def limited():
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (40000, resource.getrlimit(resource.RLIMIT_FSIZE)[1]))
        for out_dir in ("limited_new", "e"):
            before = {f: open(os.path.join(d, out_dir, f), "rb").read() for f in files_in(os.path.join(d, out_dir))}
            r = subprocess.run([exe, scene3, "-o", os.path.join(d, out_dir)], capture_output=True, text=True, timeout=120,
                               preexec_fn=limited)
            errors = [l for l in r.stderr.splitlines() if l.startswith("sss-render: ") and " pings" not in l]
            named = os.path.join(d, out_dir, "small.npy") + ": cannot be written ("
            check(r.returncode == 1 and len(errors) == 1 and errors[0].startswith("sss-render: " + named)
                  and "every.toml" not in errors[0] and errors[0].endswith("): no output written"),
                  f"{out_dir}: a failed write names the output ({r.returncode}, {errors})")
            after = {f: open(os.path.join(d, out_dir, f), "rb").read() for f in files_in(os.path.join(d, out_dir))}
            check(after == before, f"{out_dir}: no file written, the earlier files whole ({sorted(after)} against {sorted(before)})")
        # With ground range, the label images come on the ground-range grid too, pixel for pixel with its PNG.
        open(scene3, "w").write(everything.replace("label_images = true", "label_images = true\nground_range = true"))
        r = run([scene3, "-o", os.path.join(d, "g")])
        grounded = sorted(want + ["small_ground.png", "small_ground_labels_class.png", "small_ground_labels_instance.png",
                                  "small_ground_labels_legend.json"])
        check(r.returncode == 0 and files_in(os.path.join(d, "g")) == grounded, f"ground-range labels beside the ground-range image ({files_in(os.path.join(d, 'g'))}, {r.stderr})")
        if r.returncode == 0:
            size = lambda name: struct.unpack(">II", open(os.path.join(d, "g", name), "rb").read()[16:24])
            check(size("small_ground.png") == size("small_ground_labels_class.png") == size("small_ground_labels_instance.png"),
                  f"the ground-range labels have the ground-range image's size ({size('small_ground.png')}, {size('small_ground_labels_class.png')})")
        # A loaded seabed (ESRI ASCII, 0.5 m cells, a gentle slope), quantised counts and a ground-range image.
        with open(os.path.join(d, "bed.asc"), "w") as f:
            f.write("ncols 80\nnrows 80\nxllcorner 0\nyllcorner 0\ncellsize 0.5\n")
            for row in range(80):
                f.write(" ".join("%.3f" % (0.02 * c) for c in range(80)) + "\n")
        loaded = os.path.join(d, "loaded.toml")
        open(loaded, "w").write('[render]\npings = 8\n[seabed]\nfile = "bed.asc"\n[sonar]\nmax_range_m = 20\n'
                                '[motion]\nstart_m = [20, 5]\naltitude_m = 5\n[output]\nstem = "bed"\npng_scale = "quantised"\nground_range = true\n')
        r = run([loaded, "-o", "out"], cwd=d)
        check(r.returncode == 0 and files_in(os.path.join(d, "out")) == ["bed.png", "bed_ground.png"],
              f"a loaded .asc seabed renders a quantised PNG and a ground-range PNG ({files_in(os.path.join(d, 'out'))}, {r.stderr})")
        r = run([loaded, "-o", "seeded", "--seed", "3"], cwd=d)
        check(r.returncode == 1 and "--seed" in r.stderr and "seabed.file" in r.stderr and not os.path.exists(os.path.join(d, "seeded")),
              f"--seed with a loaded seabed is refused, not ignored ({r.returncode}, {r.stderr})")
        flat = os.path.join(d, "flat.toml")
        open(flat, "w").write('[render]\npings = 2\n[sonar]\nmax_range_m = 20\n')
        r = run([flat, "-o", "seeded_flat", "--seed", "3"], cwd=d)
        check(r.returncode == 1 and "--seed" in r.stderr and "[[seabed.region]]" in r.stderr and not os.path.exists(os.path.join(d, "seeded_flat")),
              f"--seed with a flat generated seabed is refused, not ignored ({r.returncode}, {r.stderr})")
        r = run([os.path.join(cli, "scenes", "primitives.toml"), "-o", os.path.join(d, "p")])
        boxes = open(os.path.join(d, "p", "prim.txt")).read().splitlines() if r.returncode == 0 else []
        check(len(boxes) == 2, f"the sphere and the cylinder each get a YOLO box ({boxes}, {r.stderr})")
        # A planar array and a trajectory (its turn.csv relative to the scene's directory, the working directory).
        scenes = os.path.join(cli, "scenes")
        r = run(["planar.toml", "-o", os.path.join(d, "pa"), "--pings", "0:6"], cwd=scenes)
        check(r.returncode == 0 and files_in(os.path.join(d, "pa")) == ["planar.png"], f"a planar-array scene renders ({r.stderr})")
        r = run(["trajectory.toml", "-o", os.path.join(d, "tr"), "--pings", "95:101"], cwd=scenes)
        check(r.returncode == 0 and files_in(os.path.join(d, "tr")) == ["turn.json", "turn.npy", "turn.png"],
              f"a trajectory scene renders up to its last ping ({r.stderr})")
        r = run(["trajectory.toml", "-o", os.path.join(d, "tx"), "--pings", "95:102"], cwd=scenes)
        check(r.returncode == 1 and "'95:102' reaches past the scene's last ping (render.pings = 101)" in r.stderr
              and files_in(os.path.join(d, "tx")) == [], f"--pings beyond the scene's pings is one error naming them ({r.stderr})")
        # precision = "double": the arrays are float64, and the labels come from the double simulator too.
        geo = open(os.path.join(scenes, "georeferenced.toml")).read().replace(
            "npy = true", "npy = true\nxtf = true\nxtf_utm_zone = 32\ncoco = true\nyolo = true\nlabel_images = true\nground_range = true")
        open(os.path.join(d, "geo.toml"), "w").write(geo)
        r = run([os.path.join(d, "geo.toml"), "-o", os.path.join(d, "geo"), "--pings", "12:20"])
        want = ["classes.txt"] + ["georeferenced" + s for s in [".json", ".npy", ".png", ".txt", ".xtf", "_coco.json", "_ground.png"]]
        want += ["georeferenced" + g + "_labels_" + s for g in ["", "_ground"] for s in ["class.png", "instance.png", "legend.json"]]
        check(r.returncode == 0 and files_in(os.path.join(d, "geo")) == sorted(want),
              f"a double scene writes every product asked ({files_in(os.path.join(d, 'geo'))}, {r.stderr})")
        if r.returncode == 0:
            npy = open(os.path.join(d, "geo", "georeferenced.npy"), "rb").read()
            check(b"'descr': '<f8'" in npy[:128] and b"(8, " in npy[:128], f"the double scene's .npy holds 8 pings of float64 ({npy[:128]})")
            check(len(open(os.path.join(d, "geo", "georeferenced.txt")).read().splitlines()) == 1, "the cylinder gets its YOLO box in double")
            # Its world is UTM zone 32 (xtf_utm_zone): the XTF's navigation is latitude and longitude there, about
            # 54.1 N and 9 E, not a plane about (0, 0) (which would put it at 4.5 E).
            xtf = open(os.path.join(d, "geo", "georeferenced.xtf"), "rb").read()
            nav_units = struct.unpack_from("<H", xtf, 164)[0]
            lat, lon = struct.unpack_from("<dd", xtf, 1024 + 160)  # SensorYcoordinate, SensorXcoordinate
            check(nav_units == 3 and 54.0 < lat < 54.3 and 9.0 < lon < 9.1,
                  f"the UTM scene's XTF navigation is latitude and longitude in zone 32 (units {nav_units}, {lat}, {lon})")
            # ThisFileName is the file's own name, not the temporary it was written under.
            name = xtf[100:164].split(b"\0")[0]
            check(name == b"georeferenced.xtf", f"the XTF's ThisFileName is its final name ({name})")
        # ... and in layered water, the survey double exists for (UTM bathymetry, a measured profile).
        open(os.path.join(d, "geo_layered.toml"), "w").write(open(os.path.join(scenes, "georeferenced.toml")).read() +
                                                             '\n[water]\nmodel = "layered"\ndepth_m = [0, 10, 30]\nspeed_mps = [1500, 1495, 1485]\n')
        r = run([os.path.join(d, "geo_layered.toml"), "-o", os.path.join(d, "geol"), "--pings", "12:14"])
        check(r.returncode == 0 and files_in(os.path.join(d, "geol")) == ["georeferenced.json", "georeferenced.npy", "georeferenced.png"],
              f"a double scene in layered water renders ({files_in(os.path.join(d, 'geol'))}, {r.stderr})")
        text = open(small).read().replace("npy = true", "npy = false").replace('stem = "small"', 'stem = "other"')
        scene2 = os.path.join(d, "other.toml")
        open(scene2, "w").write(text)
        r = run([scene2, "-o", os.path.join(d, "b"), "--pings", "4:10"])
        check(r.returncode == 0, f"second render succeeds ({r.stderr})")
        check(files_in(os.path.join(d, "b")) == ["other.png"], f"npy = false writes only the PNG ({files_in(os.path.join(d, 'b'))})")
        r = run([small, "-o", os.path.join(d, "c"), "--pings", "9:3"])
        check(r.returncode == 1 and len(r.stderr.strip().splitlines()) == 1, f"an empty --pings range is one error line ({r.stderr})")
        check(files_in(os.path.join(d, "c")) == [], "a failing command line writes nothing")
        for bad in ["-1:4", "0:1e3", "0x1:4", "0:+3", "0:10000001", "0:25", "23:25", "99999999999999990:99999999999999999"]:
            r = run([small, "-o", os.path.join(d, "c"), "--pings", bad])
            check(r.returncode == 1 and "--pings" in r.stderr and files_in(os.path.join(d, "c")) == [],
                  f"--pings {bad} is refused, naming --pings ({r.returncode}, {r.stderr})")
        for bad in ["-5", "99999999999999999999", "9223372036854775808", "1e3", ""]:
            r = run([small, "-o", os.path.join(d, "c"), "--seed", bad])
            check(r.returncode == 1 and "--seed" in r.stderr and files_in(os.path.join(d, "c")) == [],
                  f"--seed {bad!r} is refused, naming --seed, not clamped ({r.returncode}, {r.stderr})")
        for bad in ["1e3", "-1", "1025", "4.0", ""]:
            r = run([small, "-o", os.path.join(d, "c"), "--threads", bad])
            check(r.returncode == 1 and f"--threads: '{bad}' is not a whole number from 0 to 1024" in r.stderr
                  and files_in(os.path.join(d, "c")) == [], f"--threads {bad!r} is refused in its own words ({r.stderr})")
        r = run([small, "--dry-run", "--threads", "0004"])
        check(r.returncode == 0 and "threads = 4" in r.stdout, f"--threads takes leading zeros ({r.stderr})")
        r = run([small, "-o", os.path.join(d, "c"), "--pings", "100000:"])
        check(r.returncode == 1 and "starts past the scene's last ping (render.pings = " in r.stderr,
              f"--pings A: past the last ping says so ({r.stderr})")
        r = run([small, "--dry-run", "--seed", "0009223372036854775807"])
        check(r.returncode == 0 and "seed = 9223372036854775807" in r.stdout, f"--seed takes 2^63 - 1 ({r.stderr})")
        # A final name that is a directory: one error before any file is renamed, so what was there stays as it was.
        k = os.path.join(d, "k")
        os.makedirs(os.path.join(k, "small.npy"))
        open(os.path.join(k, "small.png"), "wb").write(b"old")
        r = run([small, "-o", k, "--pings", "0:2"])
        check(r.returncode == 1 and "small.npy: an output would replace this directory" in r.stderr
              and open(os.path.join(k, "small.png"), "rb").read() == b"old" and files_in(k) == ["small.npy", "small.png"],
              f"an output named like a directory changes nothing ({files_in(k)}, {r.stderr})")
        # Levels that overflow single precision: an error naming the keys, and no file.
        loud = os.path.join(d, "loud.toml")
        open(loud, "w").write(open(small).read().replace("[sonar]", "[receiver]\ntvg = true\ntvg_gain_db = 300\n\n[sonar]\nsource_level_db = 300"))
        r = run([loud, "-o", os.path.join(d, "l"), "--pings", "0:2"])
        check(r.returncode == 1 and "not finite or saturated" in r.stderr and "sonar.source_level_db" in r.stderr and files_in(os.path.join(d, "l")) == [],
              f"a render that overflows is an error, not a file of infinities ({r.stderr})")
        # A directory no file can be written in: one error before the render (no progress line), nothing made.
        r = run([small, "-o", "/proc"])
        check(r.returncode == 1 and "/proc: cannot write files in the output directory" in r.stderr and "pings" not in r.stderr,
              f"an output directory that takes no file is refused before the render ({r.stderr})")
        # YOLO's classes.txt is the directory's class list: a second scene's new class is added at its end, and the
        # first scene's indices stay right.
        y = os.path.join(d, "y")
        first_scene = open(small).read().replace("npy = true", "npy = false\nyolo = true")
        open(os.path.join(d, "y1.toml"), "w").write(first_scene)
        r = run([os.path.join(d, "y1.toml"), "-o", y, "--pings", "0:24"])
        before = open(os.path.join(y, "classes.txt")).read().splitlines() if r.returncode == 0 else []
        check(r.returncode == 0 and len(before) >= 1, f"a YOLO render writes classes.txt ({before}, {r.stderr})")
        r = run([os.path.join(cli, "scenes", "primitives.toml"), "-o", y])
        after = open(os.path.join(y, "classes.txt")).read().splitlines() if r.returncode == 0 else []
        check(r.returncode == 0 and after[:len(before)] == before and len(after) > len(before),
              f"a second scene's classes are added after the first's, which keep their place ({before} -> {after}, {r.stderr})")
        if r.returncode == 0:
            names = [after[int(line.split()[0])] for line in open(os.path.join(y, "prim.txt")).read().splitlines()]
            # Both primitives are class_id 1, named by the first of them.
            check(names == ["sphere", "sphere"] and after[0] == "lying_cylinder",
                  f"the second scene's boxes index their own class in the shared list ({after}, {names})")
        # Two classes of one name share its index, and rendering again adds nothing to the list.
        twice = open(small).read().replace("npy = true", "npy = false\nyolo = true") + (
            '\n[[object]]\ntype = "lying_cylinder"\nclass_id = 2\ncenter_m = [14, 12]\nheading_deg = 0\nlength_m = 2\nradius_m = 0.3\n')
        open(os.path.join(d, "twice.toml"), "w").write(twice)
        for _ in range(2):
            r = run([os.path.join(d, "twice.toml"), "-o", os.path.join(d, "tw")])
        names = open(os.path.join(d, "tw", "classes.txt")).read().splitlines() if r.returncode == 0 else []
        boxes = [line.split()[0] for line in open(os.path.join(d, "tw", "small.txt")).read().splitlines()] if r.returncode == 0 else []
        check(names == ["lying_cylinder"] and boxes == ["0", "0"],
              f"classes of one name share one index, and a second render adds nothing ({names}, {boxes}, {r.stderr})")
        # A failed run removes exactly the directories it made: `new` (made on the way), not `existing`.
        os.makedirs(os.path.join(d, "existing"))
        r = run([os.path.join(cli, "broken", "mine_case_below_anchor.toml"), "-o", os.path.join(d, "new", "..", "existing", "x")])
        check(r.returncode == 1 and os.path.isdir(os.path.join(d, "existing")) and not os.path.exists(os.path.join(d, "new"))
              and files_in(os.path.join(d, "existing")) == [], f"a failed run removes the directories it made, and only those ({r.stderr})")
        # A range that reaches the seabed but a beam that does not (the default fan's steepest ray, 45 degrees, meets
        # it 7.07 m out from 5 m up): a coverage warning, not a silent black image.
        open(os.path.join(d, "short.toml"), "w").write("[motion]\naltitude_m = 5\n[sonar]\nmax_range_m = 5.5\n")
        r = run([os.path.join(d, "short.toml"), "--dry-run"])
        check(r.returncode == 0 and "the beam's steepest ray (depression 45 deg) meets the seabed 5 m below at 7.071 m" in r.stderr,
              f"a beam that never reaches the seabed within the range is reported ({r.stderr})")
        # The .npy sidecar says which receiver stages made the values.
        stages = os.path.join(d, "stages.toml")
        open(stages, "w").write(open(small).read() + "\n[receiver]\ntvg = true\nspeckle = true\n")
        r = run([stages, "-o", os.path.join(d, "st"), "--pings", "0:2"])
        import json
        side = json.load(open(os.path.join(d, "st", "small.json"))) if r.returncode == 0 else {}
        check([x["stage"] for x in side.get("receiver_stages", [])] == ["speckle", "tvg"] and "after the receiver stages" in side.get("values", ""),
              f"the sidecar lists the receiver stages applied, in order ({side.get('receiver_stages')}, {r.stderr})")
        plain = json.load(open(os.path.join(d, "a", "small.json")))
        check(plain.get("receiver_stages") == [] and plain.get("values", "").startswith("mean received power"),
              f"without stages the sidecar says the values are the mean echo power ({plain.get('values')})")
        # The scene path is a directory.
        r = run([d, "-o", os.path.join(d, "m")])
        check(r.returncode == 1 and "is a directory, not a scene file" in r.stderr, f"a directory is not a scene ({r.stderr})")

elif case == "interrupt":
    # SIGINT (Ctrl-C), and SIGTERM as a batch system sends it: 128 + the signal's number, no file left.
    for sig, status in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
        with tempfile.TemporaryDirectory() as d:
            long_scene = os.path.join(d, "long.toml")
            open(long_scene, "w").write(open(small).read().replace("pings = 24", "pings = 100000").replace("altitude_m = 6", "altitude_m = 6\nspeed_mps = 0"))
            out = os.path.join(d, "o")
            p = subprocess.Popen([exe, long_scene, "-o", out], stderr=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            line = p.stderr.readline()  # the first progress line: the render is under way
            check("pings" in line, f"progress before the interrupt ({line})")
            p.send_signal(sig)
            try:
                _, rest = p.communicate(timeout=60)
            except subprocess.TimeoutExpired:
                p.kill()
                rest = ""
                check(False, f"stops within 60 s of {sig.name}")
            check(p.returncode == status, f"exit status {status} after {sig.name} (got {p.returncode})")
            check("interrupted" in rest and "no file written" in rest, f"says it was interrupted ({rest})")
            check(files_in(out) == [], f"no file left after {sig.name} ({files_in(out)})")

elif case in ("progress_tty", "progress_plain"):
    with tempfile.TemporaryDirectory() as d:
        if case == "progress_tty":
            pid, fd = pty.fork()
            if pid == 0:
                os.execv(exe, [exe, small, "-o", d])
            data = b""
            while True:
                try:
                    chunk = os.read(fd, 4096)
                except OSError:
                    break
                if not chunk:
                    break
                data += chunk
            _, status = os.waitpid(pid, 0)
            text = data.decode(errors="replace")
            check(os.waitstatus_to_exitcode(status) == 0, f"render on a terminal succeeds ({text})")
            check("\r[" in text, "the bar is redrawn in place (carriage return)")
            check(re.search(r"\[#{30}\] 24/24 pings +[0-9.]+ pings/s +ETA 0 s", text) is not None, f"the full bar shows pings, rate and ETA ({text!r})")
        else:
            r = run([small, "-o", d])
            lines = [l for l in r.stderr.splitlines() if "/24 pings" in l]
            check(r.returncode == 0, "render succeeds")
            check("\r" not in r.stderr, "no carriage returns without a terminal")
            check(len(lines) >= 2 and re.match(r"sss-render: 24/24 pings, [0-9.]+ pings/s, ETA 0 s$", lines[-1]) is not None,
                  f"plain progress lines end with every ping done ({lines})")
else:
    sys.exit(f"unknown case {case}")

sys.exit(1 if failures else 0)
