#!/bin/sh
# Usage: with_file_size_limit.sh BLOCKS COMMAND...: runs COMMAND with every file it writes limited
# to BLOCKS x 512 bytes, a full disk without privileges (SIGXFSZ ignored, so a write past the
# limit fails with EFBIG instead of ending the process), then says how this rank exited.
limit=$1
shift
ulimit -f "$limit"
trap '' XFSZ
"$@"
code=$?
echo "rank ${OMPI_COMM_WORLD_RANK:-?} exited with $code"
# mpirun ends the whole job as soon as one rank exits non-zero: let the others report first.
[ "$code" -eq 0 ] || sleep 2
exit $code
