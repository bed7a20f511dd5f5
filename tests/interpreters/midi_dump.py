#!/usr/bin/python3
"""Reads a Standard MIDI File with mido (an independent parser) and prints what it holds
as one JSON object, in absolute ticks: notes paired first-in first-out per channel and
pitch, program changes, controllers, pitch bends, tempos and time signatures, each
track's name (its first track-name meta event, or null), and the
channel messages in playing order with their times in seconds ("timeline"). Notes left
without a note-off are counted in "unmatched"."""
import json
import sys

import mido


def main(path):
    midi = mido.MidiFile(path)
    out = {"type": midi.type, "ppq": midi.ticks_per_beat, "tracks": len(midi.tracks),
           "notes": [], "programs": [], "controls": [], "bends": [], "tempos": [],
           "timesigs": [], "unmatched": 0, "track_ends": [], "channels_per_track": [],
           "track_names": []}
    for track in midi.tracks:
        tick = 0
        sounding = {}
        channels = set()
        ended = False
        name = None
        for message in track:
            tick += message.time
            if message.type == "note_on" and message.velocity > 0:
                sounding.setdefault((message.channel, message.note), []).append((tick, message.velocity))
                channels.add(message.channel)
            elif message.type in ("note_off", "note_on"):
                started = sounding.get((message.channel, message.note))
                if started:
                    on, velocity = started.pop(0)
                    out["notes"].append([on, tick, message.channel, message.note, velocity])
                channels.add(message.channel)
            elif message.type == "program_change":
                out["programs"].append([tick, message.channel, message.program])
                channels.add(message.channel)
            elif message.type == "control_change":
                out["controls"].append([tick, message.channel, message.control, message.value])
                channels.add(message.channel)
            elif message.type == "pitchwheel":
                out["bends"].append([tick, message.channel, message.pitch + 8192])
                channels.add(message.channel)
            elif message.type == "set_tempo":
                out["tempos"].append([tick, message.tempo])
            elif message.type == "time_signature":
                out["timesigs"].append([tick, message.numerator, message.denominator])
            elif message.type == "track_name" and name is None:
                name = message.name
            elif message.type == "end_of_track":
                ended = True
                out["track_ends"].append(tick)
        if not ended:
            out["track_ends"].append(-1)
        out["unmatched"] += sum(len(v) for v in sounding.values())
        out["channels_per_track"].append(sorted(channels))
        out["track_names"].append(name)
    out["notes"].sort()
    # The messages as a player sends them, in seconds through the tempo map (mido merges
    # the tracks), for comparison with what a live peer received.
    seconds = 0.0
    out["timeline"] = []
    for message in midi:
        seconds += message.time
        if not message.is_meta:
            out["timeline"].append([seconds, message.bytes()])
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv[1])
