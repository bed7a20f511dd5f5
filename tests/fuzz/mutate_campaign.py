#!/usr/bin/env python3
"""A mutation campaign against the ontogen executable (tests/fuzz/README.md).

Makes mutants of the programs under models/ and tests/programs/, and (half of them) of
the cpfg (.l) and L-Py (.lpy) files under tests/convert/, with the operators of issue 16 (tokens
deleted, duplicated and swapped; huge, tiny and non-finite numbers; truncations; random
bytes and invalid UTF-8; very deep nesting; device files and FIFOs as imports, for a .l
as its view file, and deep nesting again for a .lpy, which reads no other file) and runs `ontogen check`, `ontogen word --json --at ...` and a short
`ontogen run` on each (a .l or .lpy `ontogen convert` first), under a time limit. Each
run is classified:

  crash          ended by a signal, exit 70 (an internal error), or a sanitizer report
  hang           still running at the time limit
  unlocated      exit 1 (errors in the program) or 6 (code the converter cannot
                 translate) without any FILE:LINE:COL: error
  invalid JSON   `word --json` exited 0 and printed no valid JSON
  non-finite     a number that is not finite in an output: `null`, NaN or Infinity in
                 `word --json` (unless the program says #allow nonfinite, which prints
                 its state so), inf or NaN in a vertex of the .obj or .ply, a float
                 accessor of the .glb, or the numbers of the .svg

and the counts are printed as a Markdown table, with the mutants that failed kept in
--keep for replay. The same --seed makes the same mutants. --self-test instead runs one
model, checks that its outputs pass, plants a NaN in each and checks that each is found.

  python3 tests/fuzz/mutate_campaign.py --ontogen build/apps/ontogen --mutants 3000
  python3 tests/fuzz/mutate_campaign.py --ontogen build/apps/ontogen --self-test
"""

import argparse
import collections
import concurrent.futures
import json
import os
import random
import re
import shutil
import math
import signal
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# A token of the cell language, roughly: enough to delete, duplicate and swap whole ones.
TOKEN = re.compile(rb'"[^"\n]*"|#[A-Za-z_]+|[A-Za-z_][A-Za-z_0-9]*|[0-9]+(?:\.[0-9]*)?(?:[eE][-+]?[0-9]+)?'
                   rb'|->|-->|[<>=!]=|&&|\|\||[^\s]')
NUMBER = re.compile(rb'(?<![A-Za-z_0-9.])[0-9]+(?:\.[0-9]*)?(?:[eE][-+]?[0-9]+)?')

EXTREME_NUMBERS = [b'1e308', b'1e309', b'-1e308', b'1e-320', b'4.9e-324', b'0', b'-0', b'0/0', b'1/0', b'-1/0',
                   b'(0/0)', b'99999999999999999999', b'18446744073709551616', b'1e30', b'1e-30', b'0.0000001',
                   b'2147483648', b'-2147483649', b'1e15']
INVALID_UTF8 = [b'\xff', b'\xfe', b'\xc3', b'\xc0\xaf', b'\xed\xa0\x80', b'\xf4\x90\x80\x80', b'\xe2\x86',
                b'\xef\xbb\xbf', b'\x00', b'\x1b[31m', b'\xe2\x88\x85', b'\xce\xb2']
DEVICES = ['/dev/zero', '/dev/urandom', '/dev/null', '/dev/stdin', '/proc/self/mem', '/proc/self/status', '/']


def tokens(text):
    return [(m.start(), m.end()) for m in TOKEN.finditer(text)]


def delete_token(rng, text, _):
    spans = tokens(text)
    if not spans:
        return text
    for _ in range(rng.randint(1, 3)):
        spans = tokens(text)
        if not spans:
            break
        a, b = rng.choice(spans)
        text = text[:a] + text[b:]
    return text


def duplicate_token(rng, text, _):
    spans = tokens(text)
    if not spans:
        return text
    a, b = rng.choice(spans)
    copies = rng.choice([1, 1, 2, 10, 1000])
    return text[:b] + (b' ' + text[a:b]) * copies + text[b:]


def swap_tokens(rng, text, _):
    spans = tokens(text)
    if len(spans) < 2:
        return text
    (a, b), (c, d) = sorted(rng.sample(spans, 2))
    return text[:a] + text[c:d] + text[b:c] + text[a:b] + text[d:]


def extreme_number(rng, text, _):
    spans = [(m.start(), m.end()) for m in NUMBER.finditer(text)]
    if not spans:
        return text
    for _ in range(rng.randint(1, 3)):
        spans = [(m.start(), m.end()) for m in NUMBER.finditer(text)]
        if not spans:
            break
        a, b = rng.choice(spans)
        text = text[:a] + rng.choice(EXTREME_NUMBERS) + text[b:]
    return text


def truncate(rng, text, _):
    return text[:rng.randint(0, max(0, len(text) - 1))]


def random_bytes(rng, text, _):
    at = rng.randint(0, len(text))
    if rng.random() < 0.5:
        insert = rng.choice(INVALID_UTF8)
    else:
        insert = bytes(rng.randint(0, 255) for _ in range(rng.randint(1, 8)))
    return text[:at] + insert + text[at:]


def deep_nesting(rng, text, mutant):
    depth = rng.choice([100, 1000, 10000, 100000])
    at = rng.randint(0, len(text))
    if mutant['kind'] != '.cell':  # conditionals (C's or Python's) or parentheses for one of its numbers
        if rng.random() < 0.5:
            value = b'1?' * depth + b'1' + b':2' * depth if mutant['kind'] == '.l' else b'1 if 0 else ' * depth + b'2'
        else:
            value = b'(' * depth + b'1' + b')' * depth
        numbers = list(NUMBER.finditer(text))
        if not numbers:
            return text
        number = rng.choice(numbers)
        return text[:number.start()] + value + text[number.end():]
    kind = rng.randrange(5)
    if kind == 0:  # parentheses in an expression
        return b'#define DEEP ' + b'(' * depth + b'1' + b')' * depth + b'\n' + text
    if kind == 1:  # brackets in an axiom
        return text[:at] + b'[' * depth + b'F' + b']' * depth + text[at:]
    if kind == 2:  # nested systems
        depth = min(depth, 20000)
        return b''.join(b'system s%d {\n' % i for i in range(depth)) + b'}\n' * depth + text
    if kind == 3:  # unary minus
        return b'#define DEEP ' + b'-' * depth + b'1\n' + text
    return text[:at] + b'{' * depth + text[at:]  # unbalanced braces


def device_import(rng, text, mutant):
    target = rng.choice(DEVICES + [mutant['fifo'], mutant['fifo']])
    if mutant['kind'] == '.l':  # its view file is the device
        mutant['view'] = target
        return text
    if mutant['kind'] == '.lpy':  # (it reads no other file)
        return deep_nesting(rng, text, mutant)
    line = b'import "' + target.encode() + b'";\n'
    return line + text if rng.random() < 0.7 else text + b'\n' + line


OPERATORS = [
    ('token deleted', delete_token),
    ('token duplicated', duplicate_token),
    ('tokens swapped', swap_tokens),
    ('huge, tiny or non-finite number', extreme_number),
    ('truncated', truncate),
    ('random or invalid UTF-8 bytes', random_bytes),
    ('deep nesting', deep_nesting),
    ('device file or FIFO imported', device_import),
]

LOCATED = re.compile(r'^[^\n]*:\d+:\d+: error: ', re.MULTILINE)
SANITIZER = re.compile(r'AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|runtime error: ')


SUFFIXES = ('.cell', '.l', '.lpy')


def sources():
    found = []
    for folder in ('models', 'tests/programs', 'tests/convert'):
        for directory, _, files in os.walk(os.path.join(ROOT, folder)):
            for name in sorted(files):
                if name.endswith(SUFFIXES) and (folder == 'tests/convert') == (not name.endswith('.cell')):
                    found.append(os.path.join(directory, name))
    return sorted(found)


def run(command, cwd, timeout):
    """(outcome, exit code, stdout, stderr); outcome is 'ok', 'timeout' or 'signal'."""
    process = subprocess.Popen(command, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, start_new_session=True)
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        out, err = process.communicate()
        return 'timeout', None, out, err
    if process.returncode < 0:
        return 'signal', process.returncode, out, err
    return 'ok', process.returncode, out, err


class NonFinite(ValueError):
    """A number that is not finite where an output holds one."""


def reject_constant(name):
    raise NonFinite(name)


def json_nonfinite(value, where='$'):
    """Where the parsed JSON `value` holds a null (ontogen writes a non-finite number so),
    or None."""
    if value is None:
        return where
    if isinstance(value, float) and not math.isfinite(value):
        return where
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else ()
    for key, item in items:
        found = json_nonfinite(item, '%s.%s' % (where, key))
        if found:
            return found
    return None


def word_json_problem(out):
    """'invalid JSON', 'non-finite' or None for the output of `word --json`."""
    try:
        value = json.loads(out.decode('utf-8'), parse_constant=reject_constant)
    except NonFinite:
        return 'non-finite'
    except (UnicodeDecodeError, ValueError):
        return 'invalid JSON'
    return 'non-finite' if json_nonfinite(value) else None


def obj_nonfinite(data):
    for line in data.decode('utf-8', 'replace').splitlines():
        fields = line.split()
        if fields and fields[0] in ('v', 'vn', 'vt'):
            try:
                if not all(math.isfinite(float(f)) for f in fields[1:]):
                    return line
            except ValueError:
                return line
    return None


PLY_TYPES = {'char': 'b', 'int8': 'b', 'uchar': 'B', 'uint8': 'B', 'short': 'h', 'int16': 'h', 'ushort': 'H',
             'uint16': 'H', 'int': 'i', 'int32': 'i', 'uint': 'I', 'uint32': 'I', 'float': 'f', 'float32': 'f',
             'double': 'd', 'float64': 'd'}


def ply_nonfinite(data):
    """The first vertex property that is not finite, ASCII or binary little-endian."""
    end = data.find(b'end_header\n')
    if not data.startswith(b'ply\n') or end < 0:
        return 'no PLY header'
    header = data[:end].decode('ascii', 'replace').splitlines()
    binary = any(line.startswith('format binary_little_endian') for line in header)
    count, properties, element = 0, [], None
    for line in header:
        fields = line.split()
        if fields[:1] == ['element']:
            element = fields[1]
            if element == 'vertex':
                count = int(fields[2])
        elif fields[:1] == ['property'] and element == 'vertex' and fields[1] != 'list':
            properties.append((fields[2], PLY_TYPES[fields[1]]))
    body = data[end + len(b'end_header\n'):]
    if binary:
        row = struct.Struct('<' + ''.join(kind for _, kind in properties))
        if len(body) < count * row.size:
            return 'cut short'
        for i in range(count):
            for (name, _), value in zip(properties, row.unpack_from(body, i * row.size)):
                if isinstance(value, float) and not math.isfinite(value):
                    return 'vertex %d %s = %r' % (i, name, value)
        return None
    lines = body.decode('ascii', 'replace').splitlines()
    for i, line in enumerate(lines[:count]):
        try:
            if not all(math.isfinite(float(f)) for f in line.split()):
                return 'vertex %d: %s' % (i, line)
        except ValueError:
            return 'vertex %d: %s' % (i, line)
    return None


COMPONENTS = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3, 'VEC4': 4, 'MAT2': 4, 'MAT3': 9, 'MAT4': 16}


def glb_nonfinite(data):
    """The first float of a float accessor (or an accessor's min and max) that is not finite."""
    if len(data) < 20 or data[:4] != b'glTF':
        return 'no GLB header'
    length, kind = struct.unpack_from('<I4s', data, 12)
    if kind != b'JSON':
        return 'no JSON chunk'
    try:
        gltf = json.loads(data[20:20 + length].decode('utf-8'), parse_constant=reject_constant)
    except NonFinite:
        return 'NaN or Infinity in its JSON'
    binary = b''
    at = 20 + length
    if at + 8 <= len(data):
        chunk, kind = struct.unpack_from('<I4s', data, at)
        if kind == b'BIN\x00':
            binary = data[at + 8:at + 8 + chunk]
    views = gltf.get('bufferViews', [])
    for index, accessor in enumerate(gltf.get('accessors', [])):
        for bound in ('min', 'max'):
            if bound in accessor and json_nonfinite(accessor[bound]):
                return 'accessor %d %s' % (index, bound)
        if accessor.get('componentType') != 5126 or 'bufferView' not in accessor:
            continue
        view = views[accessor['bufferView']]
        width = COMPONENTS[accessor['type']]
        stride = view.get('byteStride', 4 * width)
        start = view.get('byteOffset', 0) + accessor.get('byteOffset', 0)
        for i in range(accessor['count']):
            for value in struct.unpack_from('<%df' % width, binary, start + i * stride):
                if not math.isfinite(value):
                    return 'accessor %d, element %d: %r' % (index, i, value)
    return None


SVG_NONFINITE = re.compile(r'="[^"]*(?<![A-Za-z])(?:-?nan|-?inf(?:inity)?)(?![A-Za-z])[^"]*"', re.IGNORECASE)


def svg_nonfinite(data):
    found = SVG_NONFINITE.search(data.decode('utf-8', 'replace'))
    return found.group(0)[:80] if found else None


OUTPUT_CHECKS = {'.obj': obj_nonfinite, '.ply': ply_nonfinite, '.glb': glb_nonfinite, '.svg': svg_nonfinite}


def outputs_nonfinite(folder):
    """(file, what) of the first output under `folder` that holds a non-finite number."""
    for directory, _, files in os.walk(folder):
        for name in sorted(files):
            check = OUTPUT_CHECKS.get(os.path.splitext(name)[1])
            if check:
                with open(os.path.join(directory, name), 'rb') as file:
                    what = check(file.read())
                if what:
                    return name, what
    return None


def classify(command_name, outcome, code, out, err, allows_nonfinite=False):
    text = err.decode('utf-8', 'replace')
    if outcome == 'signal' or code == 70 or SANITIZER.search(text):
        return 'crash'
    if outcome == 'timeout':
        return 'hang'
    if code in (1, 6) and not LOCATED.search(text):
        return 'unlocated'
    if command_name == 'word' and code == 0:
        problem = word_json_problem(out)
        if problem and not (problem == 'non-finite' and allows_nonfinite):
            return problem
    return None


def campaign_one(job):
    index, operator_name, path, ontogen, timeout, work = job
    folder = os.path.join(work, 'm%05d' % index)
    commands = {}
    if not path.endswith('.cell'):
        commands['convert'] = [ontogen, 'convert', path]
    commands.update({
        'check': [ontogen, 'check', path],
        'word': [ontogen, 'word', path, '--json', '--at', '0,1,2.5', '--max-cells', '100000'],
        'run': [ontogen, 'run', path, '--until', '2', '--frames', '2', '--format', 'glb,obj,ply,svg', '--size',
                '64x64', '--max-cells', '100000', '--out', os.path.join(folder, 'out')],
    })
    with open(path, 'rb') as file:
        allows_nonfinite = re.search(rb'#allow\s+nonfinite', file.read()) is not None
    results = []
    for name, command in commands.items():
        outcome, code, out, err = run(command, folder, timeout)
        verdict = classify(name, outcome, code, out, err, allows_nonfinite)
        if name == 'run' and not verdict:
            found = outputs_nonfinite(os.path.join(folder, 'out'))
            if found:
                verdict = 'non-finite'
                err += ('\n%s holds %s' % found).encode()
        results.append((name, code, verdict, err[-2000:]))
    return index, operator_name, path, results


def plant_nan(name, data):
    """`data` of the output `name` with its first number (a vertex's, a float accessor's,
    a coordinate's) made NaN."""
    extension = os.path.splitext(name)[1]
    if extension == '.obj':
        return re.sub(rb'^(v \S+)', b'v nan', data, count=1, flags=re.MULTILINE)
    if extension == '.svg':
        return re.sub(rb'(<(?!svg\b|\?xml)[a-z]+\b[^>]*?="[^"0-9-]*)-?[0-9.]+', rb'\1NaN', data, count=1)
    if extension == '.ply':
        at = data.index(b'end_header\n') + len(b'end_header\n')
        if b'format ascii' in data[:at]:
            return data[:at] + re.sub(rb'^\S+', b'nan', data[at:], count=1)
        return data[:at] + struct.pack('<f', float('nan')) + data[at + 4:]
    if extension == '.glb':
        length = struct.unpack_from('<I', data, 12)[0]
        gltf = json.loads(data[20:20 + length])
        accessor = next(a for a in gltf['accessors'] if a.get('componentType') == 5126 and 'bufferView' in a)
        view = gltf['bufferViews'][accessor['bufferView']]
        at = 20 + length + 8 + view.get('byteOffset', 0) + accessor.get('byteOffset', 0)
        return data[:at] + struct.pack('<f', float('nan')) + data[at + 4:]
    raise ValueError(name)


def self_test(ontogen):
    """Runs a model whose outputs must pass, plants a NaN in each output (and in the
    word's JSON) and checks that each is found; 0 when all are."""
    work = tempfile.mkdtemp(prefix='ontogen-self-test-')
    failures = []
    try:
        model = os.path.join(ROOT, 'models', 'flower.cell')  # lines, a surface: every output has numbers
        out = os.path.join(work, 'out')
        outcome, code, _, err = run([ontogen, 'run', model, '--until', '2', '--frames', '2', '--format',
                                     'glb,obj,ply,svg', '--size', '64x64', '--out', out], work, 120)
        if outcome != 'ok' or code != 0:
            return 'the run failed: %s' % err.decode('utf-8', 'replace')
        written = sorted(name for name in os.listdir(out) if os.path.splitext(name)[1] in OUTPUT_CHECKS)
        kinds = {os.path.splitext(name)[1] for name in written}
        if kinds != set(OUTPUT_CHECKS):
            failures.append('outputs %s, not one of each of %s' % (sorted(kinds), sorted(OUTPUT_CHECKS)))
        found = outputs_nonfinite(out)
        if found:
            failures.append('the outputs as written are flagged: %s holds %s' % found)
        for name in written:
            path = os.path.join(out, name)
            with open(path, 'rb') as file:
                data = file.read()
            planted = plant_nan(name, data)
            if planted == data:
                failures.append('%s: no number to plant a NaN in' % name)
                continue
            with open(path, 'wb') as file:
                file.write(planted)
            if outputs_nonfinite(out) is None:
                failures.append('%s: the planted NaN is not found' % name)
            with open(path, 'wb') as file:
                file.write(data)
        outcome, code, word, err = run([ontogen, 'word', model, '--json', '--at', '0,1,2.5'], work, 120)
        if classify('word', outcome, code, word, err) is not None:
            failures.append('word --json as written is flagged')
        number = re.search(rb'(?<=[:\[,])-?[0-9][0-9.e+-]*(?=[,\]}])', word)
        for planted in (b'NaN', b'Infinity', b'null'):
            if classify('word', 'ok', 0, word[:number.start()] + planted + word[number.end():], b'') != 'non-finite':
                failures.append('word --json with %s planted is not flagged' % planted.decode())
        if classify('word', 'ok', 0, word[:number.start()] + b'null' + word[number.end():], b'', True) is not None:
            failures.append('word --json with null planted is flagged where #allow nonfinite allows it')
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return '; '.join(failures)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--ontogen', default=os.path.join(ROOT, 'build', 'apps', 'ontogen'))
    parser.add_argument('--mutants', type=int, default=3000)
    parser.add_argument('--seed', type=int, default=16)
    parser.add_argument('--timeout', type=float, default=20, help='seconds per command')
    parser.add_argument('--jobs', type=int, default=1)
    parser.add_argument('--keep', default=os.path.join(ROOT, 'build', 'mutants'),
                        help='folder for the mutants that failed')
    parser.add_argument('--self-test', action='store_true',
                        help='check that a NaN planted in each kind of output is found, and run no campaign')
    args = parser.parse_args()
    ontogen = os.path.abspath(args.ontogen)
    if args.self_test:
        failed = self_test(ontogen)
        print('self-test: ' + (failed or 'a NaN planted in each output (.obj, .ply, .glb, .svg, word --json) is found, '
                                          'and none in the outputs as written'))
        return 1 if failed else 0
    rng = random.Random(args.seed)
    programs = sources()
    native = [path for path in programs if path.endswith('.cell')]
    foreign = [path for path in programs if not path.endswith('.cell')]
    work = tempfile.mkdtemp(prefix='ontogen-mutants-')
    fifo = os.path.join(work, 'fifo.cell')
    os.mkfifo(fifo)
    jobs = []
    try:
        for index in range(args.mutants):
            operator_name, operator = OPERATORS[index % len(OPERATORS)]
            # Half the mutants are of .l and .lpy files, far fewer than the .cell programs.
            source = rng.choice(foreign if foreign and rng.random() < 0.5 else native)
            with open(source, 'rb') as file:
                text = file.read()
            # What an operator knows of the mutant beside its text, and may set ('view').
            about = {'fifo': fifo, 'kind': os.path.splitext(source)[1]}
            mutant = operator(rng, text, about)
            folder = os.path.join(work, 'm%05d' % index)
            os.makedirs(folder)
            # Imports, #surface and view files relative to the program find those beside the
            # original; a mutant that names a device as its view has that in its place.
            path = os.path.join(folder, os.path.basename(source))
            view = os.path.splitext(path)[0] + '.v'
            for entry in os.listdir(os.path.dirname(source)):
                if not entry.endswith(SUFFIXES):
                    os.symlink(os.path.join(os.path.dirname(source), entry), os.path.join(folder, entry))
            if 'view' in about:
                if os.path.lexists(view):
                    os.remove(view)
                os.symlink(about['view'], view)
            with open(path, 'wb') as file:
                file.write(mutant)
            jobs.append((index, operator_name, path, ontogen, args.timeout, work))

        counts = collections.OrderedDict((name, collections.Counter()) for name, _ in OPERATORS)
        mutants = collections.Counter()
        failures = []
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            for index, operator_name, path, results in pool.map(campaign_one, jobs):
                mutants[operator_name] += 1
                for name, code, verdict, err in results:
                    counts[operator_name]['runs'] += 1
                    counts[operator_name]['exit %s' % code] += 1
                    if verdict:
                        counts[operator_name][verdict] += 1
                        failures.append((index, operator_name, name, verdict, path, err))
                shutil.rmtree(os.path.join(work, 'm%05d' % index, 'out'), ignore_errors=True)

        if failures:
            os.makedirs(args.keep, exist_ok=True)
        for index, operator_name, name, verdict, path, err in failures:
            kept = os.path.join(args.keep, 'm%05d_%s%s' % (index, name, os.path.splitext(path)[1]))
            shutil.copyfile(path, kept)
            print('%s: %s %s (%s)\n%s' % (kept, name, verdict, operator_name,
                                          err.decode('utf-8', 'replace')[-600:]), file=sys.stderr)

        print('Mutation campaign: %d mutants of %d programs (models/, tests/programs/; .l and .lpy of '
              'tests/convert/), seed %d, 3 commands each (check; word --json --at 0,1,2.5; run --until 2; '
              'a .l or .lpy convert first), %g s limit per command.\n'
              % (args.mutants, len(programs), args.seed, args.timeout))
        print('| operator | mutants | runs | exit 0 | exit 1 | exit 2 | exit 3 | exit 4 | exit 6 | crash | hang '
              '| exit 1 or 6 unlocated | invalid JSON | non-finite |')
        print('|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|')
        total = collections.Counter()
        for operator_name, count in counts.items():
            total.update(count)
            total['mutants'] += mutants[operator_name]
            count['mutants'] = mutants[operator_name]
            print(row(operator_name, count))
        print(row('**all**', total))
        other = sorted(k for k in total if k.startswith('exit ') and k not in
                       ('exit 0', 'exit 1', 'exit 2', 'exit 3', 'exit 4', 'exit 6'))
        if other:
            print('\nOther exits: ' + ', '.join('%s: %d' % (k, total[k]) for k in other))
        return 1 if failures else 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


def row(name, count):
    cells = [name, count['mutants'], count['runs']] + [count['exit %d' % c] for c in (0, 1, 2, 3, 4, 6)] + \
        [count['crash'], count['hang'], count['unlocated'], count['invalid JSON'], count['non-finite']]
    return '| ' + ' | '.join(str(c) for c in cells) + ' |'


if __name__ == '__main__':
    sys.exit(main())
