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

and the counts are printed as a Markdown table, with the mutants that failed kept in
--keep for replay. The same --seed makes the same mutants.

  python3 tests/fuzz/mutate_campaign.py --ontogen build/apps/ontogen --mutants 3000
"""

import argparse
import collections
import concurrent.futures
import json
import os
import random
import re
import shutil
import signal
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


def classify(command_name, outcome, code, out, err):
    text = err.decode('utf-8', 'replace')
    if outcome == 'signal' or code == 70 or SANITIZER.search(text):
        return 'crash'
    if outcome == 'timeout':
        return 'hang'
    if code in (1, 6) and not LOCATED.search(text):
        return 'unlocated'
    if command_name == 'word' and code == 0:
        try:
            json.loads(out.decode('utf-8'))
        except (UnicodeDecodeError, ValueError):
            return 'invalid JSON'
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
    results = []
    for name, command in commands.items():
        outcome, code, out, err = run(command, folder, timeout)
        results.append((name, code, classify(name, outcome, code, out, err), err[-2000:]))
    return index, operator_name, path, results


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--ontogen', default=os.path.join(ROOT, 'build', 'apps', 'ontogen'))
    parser.add_argument('--mutants', type=int, default=3000)
    parser.add_argument('--seed', type=int, default=16)
    parser.add_argument('--timeout', type=float, default=20, help='seconds per command')
    parser.add_argument('--jobs', type=int, default=1)
    parser.add_argument('--keep', default=os.path.join(ROOT, 'build', 'mutants'),
                        help='folder for the mutants that failed')
    args = parser.parse_args()
    ontogen = os.path.abspath(args.ontogen)
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
              '| exit 1 or 6 unlocated | invalid JSON |')
        print('|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|')
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
        [count['crash'], count['hang'], count['unlocated'], count['invalid JSON']]
    return '| ' + ' | '.join(str(c) for c in cells) + ' |'


if __name__ == '__main__':
    sys.exit(main())
