#!/usr/bin/env bash
# Measures the timing of live MIDI playback against a real peer on a headless machine:
# a JACK server with the dummy backend and jack_midi_dump recording what arrives
# (Debian's jackd2). Prints ontogen's own lateness at sending (--stats) and the error of
# each arrival against the schedule, from the MIDI file read by python3-mido; with
# --midi-clock also the spacing of the clocks as they arrived (the figure the tests
# report but do not assert, since a busy machine moves it by percents).
#   bash bench/live_midi_timing.sh build/apps/ontogen models/swell.cell [run options...]
set -euo pipefail
ontogen=$(realpath "$1"); model=$(realpath "$2"); shift 2
work=$(mktemp -d)
export JACK_DEFAULT_SERVER="ontogen_timing_$$"
jackd -R -n "$JACK_DEFAULT_SERVER" -d dummy -r 48000 -p 256 >"$work/jackd.log" 2>&1 &
jackd_pid=$!
dump_pid=""
cleanup() {
  [[ -n "$dump_pid" ]] && kill "$dump_pid" 2>/dev/null || true
  kill "$jackd_pid" 2>/dev/null || true
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
jack_wait -w -t 10 >/dev/null 2>&1
stdbuf -oL jack_midi_dump -a >"$work/dump.txt" 2>/dev/null &
dump_pid=$!
until jack_lsp 2>/dev/null | grep -q midi-monitor:input; do sleep 0.05; done
"$ontogen" run "$model" --interpret music --midi-port midi-monitor:input --stats --out "$work/out" "$@" 2>&1 |
  grep -E "^(playing|live:)"
sleep 0.3
kill "$dump_pid"; wait "$dump_pid" 2>/dev/null || true; dump_pid=""
stem=$(basename "$model" .cell)
/usr/bin/python3 - "$work/out/$stem.mid" "$work/dump.txt" <<'PY'
import math, sys
import mido
sent = []
t = 0.0
tempo = 500000  # microseconds a beat, MIDI's default
for message in mido.MidiFile(sys.argv[1]):
    t += message.time
    if message.type == "set_tempo" and t == 0:
        tempo = message.tempo
    if not message.is_meta:
        sent.append((t, tuple(message.bytes())))
got = []
for line in open(sys.argv[2]):
    head, _, rest = line.partition(":")
    if not head.strip().isdigit():
        continue
    fields = []
    for word in rest.split():
        if len(word) == 2 and all(c in "0123456789abcdef" for c in word):
            fields.append(int(word, 16))
        else:
            break
    got.append((int(head) / 48000.0, tuple(fields)))
clocks = [time for time, data in got if data == (0xF8,)]
got = [(time, data) for time, data in got if data and data[0] < 0xF0]  # the notes, as the file holds them
# Match the k-th occurrence of each message; errors from the first message's time.
index = {}
for k, (time, data) in enumerate(got):
    index.setdefault(data, []).append(time)
pairs = []
seen = {}
for time, data in sent:
    n = seen.get(data, 0)
    seen[data] = n + 1
    if n < len(index.get(data, [])):
        pairs.append((time - sent[0][0], index[data][n] - got[0][0]))
errors = sorted(abs(b - a) for a, b in pairs)
# The dummy backend's frame clock is not the system clock: under load it loses cycles.
# A straight line through (schedule, arrival) takes out a steady rate difference; what
# is left is jitter.
n = len(pairs)
mx = sum(a for a, _ in pairs) / n
my = sum(b for _, b in pairs) / n
sxx = sum((a - mx) ** 2 for a, _ in pairs) or 1.0
slope = sum((a - mx) * (b - my) for a, b in pairs) / sxx
residuals = sorted(abs(b - (my + slope * (a - mx))) for a, b in pairs)
missing = len(sent) - len(errors)
median = errors[len(errors) // 2]
p99 = errors[max(0, math.ceil(0.99 * len(errors)) - 1)]
print(f"arrivals: {len(got)} of {len(sent)} messages ({missing} missing); error against the schedule: "
      f"median {median * 1e3:.2f} ms, p99 {p99 * 1e3:.2f} ms, max {errors[-1] * 1e3:.2f} ms")
r99 = residuals[max(0, math.ceil(0.99 * n) - 1)]
print(f"frame clock rate against the schedule {slope:.5f}; jitter around it: median "
      f"{residuals[n // 2] * 1e3:.2f} ms, p99 {r99 * 1e3:.2f} ms")
if len(clocks) > 1:
    gaps = sorted(b - a for a, b in zip(clocks, clocks[1:]))
    spacing = (clocks[-1] - clocks[0]) / (len(clocks) - 1)
    print(f"MIDI clock: {len(clocks)} clocks, mean spacing {spacing * 1e3:.3f} ms against {tempo / 24e3:.3f} ms "
          f"({(spacing / (tempo / 24e6) - 1) * 100:+.2f} %), gaps from {gaps[0] * 1e3:.2f} to {gaps[-1] * 1e3:.2f} ms")
PY
