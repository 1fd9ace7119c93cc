#!/bin/sh
# tests/mpi/mpi_test.sh BIN NOMPI_BAKE WORKDIR LUMO_MPI — lumo-bake under
# mpirun (docs/server.md "Bakes on a cluster"): packages and reference
# images byte-identical to the single-process run at 1, 2 and 4 ranks (and
# with a resumed checkpoint); a rank killed mid-bake fails the job with a
# clear message and leaves no package; a checkpoint of another bake and a
# rank with another scene are refused; the build without MPI bakes the same
# bytes alone and refuses to run as N copies. Prints "RESULT: N passed, M failed".
bin=$1; nompi=$2; dir=$3; have_mpi=$4
mkdir -p "$dir"
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
same() {  # same NAME A B
    if cmp -s "$2" "$3"; then ok "$1"; else bad "$1 ($2 and $3 differ)"; fi
}
bake=$bin/lumo-bake
if [ "$have_mpi" != 1 ] || ! command -v mpirun >/dev/null 2>&1; then
    bad "no MPI: lumo-bake was built without Open MPI or mpirun is missing (sh tools/setup.sh installs both)"
    echo "RESULT: $pass passed, $fail failed"; exit 1
fi
# Root in a container needs --allow-run-as-root; this machine has 2 cores,
# so 4 ranks need --oversubscribe (docs/server.md).
root=""; [ "$(id -u)" -eq 0 ] && root="--allow-run-as-root"
mpi() { np=$1; shift; timeout 300 mpirun $root --oversubscribe -np "$np" "$@"; }

scene="--default --dragon build/data/models/dragon_11k.ply --grid 10 --spp 32 --seed 7 --no-progress"
rm -f "$dir"/*.lumo "$dir"/*.png "$dir"/*.partial
"$bake" $scene --threads 2 -o "$dir/single.lumo" 2>"$dir/single.err" || bad "single-process bake"
"$nompi" $scene --threads 1 -o "$dir/nompi.lumo" 2>"$dir/nompi.err" || bad "bake without MPI"
same "the build without MPI bakes the same bytes" "$dir/single.lumo" "$dir/nompi.lumo"
for np in 1 2 4; do
    mpi $np "$bake" $scene --threads 1 -o "$dir/np$np.lumo" 2>"$dir/np$np.err" || bad "mpirun -np $np"
    same "mpirun -np $np: package byte-identical to one process" "$dir/single.lumo" "$dir/np$np.lumo"
done
mpi 2 "$bake" $scene --threads 2 -o "$dir/np2t2.lumo" 2>"$dir/np2t2.err"
same "mpirun -np 2 x 2 threads: package byte-identical" "$dir/single.lumo" "$dir/np2t2.lumo"
if grep -q "ivg over 4 ranks, chunks (bytes) per rank:" "$dir/np4.err" &&
   grep -q "4 ranks x 1 threads" "$dir/np4.err"; then
    ok "4 ranks report their chunks and bytes: $(grep 'per rank' "$dir/np4.err")"
else
    bad "4-rank summary"; sed 's/^/    /' "$dir/np4.err"
fi

ref="--default --dragon build/data/models/dragon_11k.ply --reference 48x40 --spp 4 --no-progress"
"$bake" $ref --threads 2 -o "$dir/ref.png" 2>/dev/null || bad "reference in one process"
mpi 3 "$bake" $ref --threads 1 -o "$dir/ref3.png" 2>/dev/null || bad "reference over 3 ranks"
same "mpirun -np 3: reference image byte-identical" "$dir/ref.png" "$dir/ref3.png"
rm -rf "$dir/rck"
mpi 2 "$bake" $ref --threads 1 --checkpoint "$dir/rck" -o "$dir/refck.png" 2>/dev/null || bad "reference over 2 ranks, checkpoint"
"$bake" $ref --threads 2 --checkpoint "$dir/rck" -o "$dir/refck1.png" 2>"$dir/refck1.err"
if grep -q "reference.ckpt: \([0-9]*\) of \1 chunks resumed" "$dir/refck1.err"; then
    ok "the reference's checkpoint from 2 ranks resumes whole in one process"
else
    bad "reference checkpoint"; sed 's/^/    /' "$dir/refck1.err"
fi
same "reference from the checkpoint byte-identical" "$dir/ref.png" "$dir/refck1.png"

# A rank with another scene (MPMD: rank 1 gets another model) is refused.
mpirun $root --oversubscribe -np 1 "$bake" $scene -o "$dir/mixed.lumo" : \
    -np 1 "$bake" --default --dragon build/data/models/bunny.obj --grid 10 --spp 32 --seed 7 --no-progress \
    -o "$dir/mixed.lumo" >"$dir/mixed.out" 2>&1
st=$?
if [ $st -ne 0 ] && grep -q "rank 1 has another ivg work" "$dir/mixed.out" && [ ! -e "$dir/mixed.lumo" ]; then
    ok "a rank with another scene is refused (status $st)"
else
    bad "rank with another scene (status $st)"; sed 's/^/    /' "$dir/mixed.out" | head -20
fi

# The build without MPI, started as 2 copies by mpirun, refuses.
mpi 2 "$nompi" $scene -o "$dir/copies.lumo" >"$dir/copies.out" 2>&1
st=$?
if [ $st -ne 0 ] && grep -q "built without MPI" "$dir/copies.out" && [ ! -e "$dir/copies.lumo" ]; then
    ok "the build without MPI refuses to run as 2 copies"
else
    bad "no-MPI build under mpirun (status $st)"; sed 's/^/    /' "$dir/copies.out" | head
fi

# A rank killed mid-bake: the job fails with a message, no package; the
# checkpoint it left resumes (with another rank count) to the same bytes.
long="--default --dragon build/data/models/dragon_11k.ply --grid 14 --spp 1600 --seed 3 --no-progress"
ck="$dir/ckpt"; rm -rf "$ck"
"$bake" $long --threads 2 -o "$dir/long.lumo" 2>/dev/null || bad "long bake in one process"
mpirun $root --oversubscribe -np 2 "$bake" $long --threads 1 --checkpoint "$ck" -o "$dir/killed.lumo" \
    >"$dir/killed.out" 2>&1 &
job=$!
killed=""
for _ in $(seq 1 600); do   # until the checkpoint holds a few chunks, at most 60 s
    size=$(stat -c %s "$ck/ivg.ckpt" 2>/dev/null || echo 0)
    if [ "$size" -gt 20000 ]; then
        for p in $(pgrep -P $job); do
            if tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=1"; then
                kill -9 "$p" && killed=$p
            fi
        done
        break
    fi
    sleep 0.1
done
wait $job; st=$?
if [ -n "$killed" ] && [ $st -ne 0 ] && [ ! -e "$dir/killed.lumo" ] && [ ! -e "$dir/killed.lumo.partial" ] &&
   grep -q "no output written\|exited on signal 9" "$dir/killed.out"; then
    ok "rank 1 killed mid-bake: job failed (status $st), no package: $(grep -m1 'lumo-bake: error\|signal 9' "$dir/killed.out")"
else
    bad "killed rank (killed '$killed', status $st)"; sed 's/^/    /' "$dir/killed.out" | head -20
fi
mpi 3 "$bake" $long --threads 1 --checkpoint "$ck" -o "$dir/resumed.lumo" 2>"$dir/resumed.err"
resumed=$(sed -n 's/.*ivg.ckpt: \([0-9]*\) of \([0-9]*\) chunks resumed/\1/p' "$dir/resumed.err")
total=$(sed -n 's/.*ivg.ckpt: \([0-9]*\) of \([0-9]*\) chunks resumed/\2/p' "$dir/resumed.err")
if [ -n "$resumed" ] && [ "$resumed" -gt 0 ] && [ "$resumed" -lt "$total" ]; then
    ok "resumed $resumed of $total chunks from the killed run's checkpoint (3 ranks)"
else
    bad "resume ('$resumed' of '$total')"; sed 's/^/    /' "$dir/resumed.err"
fi
same "resumed package byte-identical to the uninterrupted bake" "$dir/long.lumo" "$dir/resumed.lumo"
"$bake" $long --threads 2 --checkpoint "$ck" -o "$dir/again.lumo" 2>"$dir/again.err"
grep -q "$total of $total chunks resumed" "$dir/again.err" && ok "a finished checkpoint resumes whole" ||
    bad "finished checkpoint"
same "package from a whole checkpoint byte-identical" "$dir/long.lumo" "$dir/again.lumo"
"$bake" $long --seed 4 --checkpoint "$ck" -o "$dir/other.lumo" 2>"$dir/other.err"; st=$?
# one error line (after the plan line lumo-bake says before every bake)
if [ $st -eq 1 ] && [ "$(grep -c 'error' "$dir/other.err")" -eq 1 ] && grep -q "not the checkpoint of this bake" "$dir/other.err"; then
    ok "another bake's checkpoint refused: $(grep error "$dir/other.err")"
else
    bad "another bake's checkpoint (status $st)"; sed 's/^/    /' "$dir/other.err"
fi
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
