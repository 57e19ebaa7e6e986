#!/usr/bin/env bash
# Smoke tests of the probing plots: scripts/plot_probe.py and scripts/plot_probe_sweep.py run
# with /usr/bin/python3 on tiny generated inputs must write a PNG, and must refuse malformed
# files with a one-line message naming the file and the line.
# usage: plot_scripts_check.sh CASE SCRIPTS_DIR WORK_DIR
set -euo pipefail
case_name=$1
scripts=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$work"

fail() { echo "FAIL ($case_name): $*" >&2; exit 1; }

is_png() {  # the 8-byte PNG signature, and more than a header
    [ -s "$1" ] || fail "$1 missing or empty"
    [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "$1 is not a PNG"
    [ "$(stat -c %s "$1")" -gt 10000 ] || fail "$1 is suspiciously small"
}

# Expects the command to exit non-zero with exactly one line on stderr containing $1.
expect_error() {
    local want=$1; shift
    local rc=0
    "$@" 2>err.txt >/dev/null || rc=$?
    [ "$rc" -ne 0 ] || fail "expected failure: $*"
    [ "$(wc -l < err.txt)" -eq 1 ] || fail "not a one-line error: $(cat err.txt)"
    grep -qF -- "$want" err.txt || fail "error lacks '$want': $(cat err.txt)"
}

# A torus (triangles), a square (closed polyline, z = 0) and paths around both: random walks
# inside the bounding ball/disc and an arc outside it, as `l` statements (one continued).
make_inputs() {
    /usr/bin/python3 - <<'PY'
import math, random
rnd = random.Random(1)
R, r, nu, nv = 1.0, 0.35, 32, 12
with open("torus.obj", "w") as f:
    for i in range(nu):
        for j in range(nv):
            u, v = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            f.write(f"v {(R + r * math.cos(v)) * math.cos(u)} {(R + r * math.cos(v)) * math.sin(u)} {r * math.sin(v)}\n")
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            f.write(f"f {a + 1} {b + 1} {c + 1}\nf {a + 1} {c + 1} {d + 1}\n")

def walk(f, n, dim, scale):
    p = [0.0, 0.0, 0.0]
    for _ in range(n):
        for k in range(dim):
            p[k] = max(-scale, min(scale, p[k] + rnd.uniform(-0.1, 0.1)))
        f.write(f"v {p[0]} {p[1]} {p[2]}\n")

for name, dim, scale, big in [("path3d.obj", 3, 0.9, 2.0), ("path2d.obj", 2, 0.6, 1.6)]:
    with open(name, "w") as f:
        f.write("# a probing path\n")
        walk(f, 2000, dim, scale)
        for k in range(50):  # an exterior arc
            t = math.pi * k / 49
            f.write(f"v {big * math.cos(t)} {big * math.sin(t)} 0\n")
        f.write("l " + " ".join(str(i) for i in range(1, 1001)) + "\n")
        f.write("l " + " ".join(str(i) for i in range(1001, 1501)) + " \\\n")
        f.write(" ".join(str(i) for i in range(1501, 2001)) + "\n")
        for i in range(2001, 2050):
            f.write(f"l {i} {i + 1}\n")
with open("square.obj", "w") as f:
    f.write("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nl 1 2 3 4 1\n")
PY
}

case "$case_name" in
probe_3d)
    make_inputs
    /usr/bin/python3 "$scripts/plot_probe.py" out3d.png torus.obj path3d.obj --title "torus (1, 0.35)" > log.txt
    is_png out3d.png
    grep -q "wrote out3d.png" log.txt || fail "no 'wrote' line"
    ;;
probe_2d)
    make_inputs
    /usr/bin/python3 "$scripts/plot_probe.py" out2d.png square.obj path2d.obj > log.txt
    is_png out2d.png
    ;;
probe_bad)
    make_inputs
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' > bad_index.obj
    expect_error "bad_index.obj:4:" /usr/bin/python3 "$scripts/plot_probe.py" o.png bad_index.obj path3d.obj
    printf 'v 0 0 0\nv 1 zero 0\n' > bad_number.obj
    expect_error "bad_number.obj:2:" /usr/bin/python3 "$scripts/plot_probe.py" o.png torus.obj bad_number.obj
    printf 'v 0 0 0\nv 1 0 0\n\nl 1 \\\n' > bad_continued.obj
    expect_error "bad_continued.obj:4:" /usr/bin/python3 "$scripts/plot_probe.py" o.png torus.obj bad_continued.obj
    printf 'v 0 0 0\nv 1 0 0\nl 1\n' > short_line.obj
    expect_error "short_line.obj:3:" /usr/bin/python3 "$scripts/plot_probe.py" o.png torus.obj short_line.obj
    expect_error "missing.obj" /usr/bin/python3 "$scripts/plot_probe.py" o.png torus.obj missing.obj
    [ ! -e o.png ] || fail "a PNG was written for a bad input"
    ;;
skin)
    make_inputs
    /usr/bin/python3 -c "
import math
with open('rho.txt', 'w') as f:
    for i in range(32 * 12):
        f.write(f'{0.1 + 0.3 * (1 + math.sin(i / 7.0))}\\n')
"
    /usr/bin/python3 "$scripts/plot_skin.py" skin.png torus.obj rho.txt --title "torus by rho" > log.txt
    is_png skin.png
    grep -q "wrote skin.png" log.txt || fail "no 'wrote' line"
    ;;
skin_bad)
    make_inputs
    printf '0.5\n0.5\n' > short.txt
    expect_error "short.txt: 2 values for 384 vertices" /usr/bin/python3 "$scripts/plot_skin.py" o.png torus.obj short.txt
    /usr/bin/python3 -c "print('\n'.join(['0.5'] * 100 + ['half'] + ['0.5'] * 283))" > word.txt
    expect_error "word.txt:101: not a number" /usr/bin/python3 "$scripts/plot_skin.py" o.png torus.obj word.txt
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' > bad_index.obj
    printf '1\n1\n1\n' > three.txt
    expect_error "bad_index.obj:4:" /usr/bin/python3 "$scripts/plot_skin.py" o.png bad_index.obj three.txt
    [ ! -e o.png ] || fail "a PNG was written for a bad input"
    ;;
sweep)
    cat > sweep.csv <<'CSV'
# surface,eps,... one row per run
surface,eps,vertices,probes,cells_created,detection_edges,positioning_edges,path_length,hausdorff,hausdorff_bound,seconds,extra
sphere,0.16,330,1700,9000,3000,6000,40.5,0.0125,0.0129,0.05,x
sphere,0.08,1311,6759,41000,13000,27000,160.2,0.00318,0.0032,0.21,x
sphere,0.04,5200,27000,190000,52000,110000,650,0.0008,0.0008,0.9,x
torus,0.06,2600,95000,120000,41000,98000,210,0.002,0.0021,0.5,x
torus,0.03,10152,378000,560000,163000,393000,830,0.0005,0.00052,2.4,x
torus,0.015,40100,1500000,2500000,650000,1570000,3300,nan,0.00013,10.5,x
CSV
    /usr/bin/python3 "$scripts/plot_probe_sweep.py" sweep.png sweep.csv --title "probing sweep" > log.txt
    is_png sweep.png
    ;;
sweep_bad)
    printf 'surface,eps,vertices\nsphere,0.1,10\n' > few_columns.csv
    expect_error "few_columns.csv:1: the header lacks the column(s) probes" \
        /usr/bin/python3 "$scripts/plot_probe_sweep.py" o.png few_columns.csv
    printf 'surface,eps,vertices,probes,cells_created,detection_edges,positioning_edges,path_length,hausdorff,hausdorff_bound,seconds\nsphere,0.1,10,20,30,1,2,3,0.1,0.1,1\nsphere,0.05,40,ten,30,1,2,3,0.1,0.1,1\n' > bad_number.csv
    expect_error "bad_number.csv:3: column probes" \
        /usr/bin/python3 "$scripts/plot_probe_sweep.py" o.png bad_number.csv
    [ ! -e o.png ] || fail "a PNG was written for a bad input"
    ;;
*)
    fail "unknown case"
    ;;
esac
echo "ok: $case_name"
