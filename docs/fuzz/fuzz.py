#!/usr/bin/env python3
"""Mutation fuzzer for `contact run/check` scenes and Radioss decks (1 core, sequential)."""
import json, os, random, re, shutil, subprocess, sys, time, hashlib

BIN = '/tmp/fuzz/wt/build/gcc-double-asan/bin/contact'
SEEDS = '/tmp/fuzz/seeds'
WORK = '/tmp/fuzz/cases'
FIND = '/tmp/fuzz/findings'
LOG = '/tmp/fuzz/log.jsonl'
DECKS = ['int357.rad', 'tri.rad', 'brick.rad']

ENV = dict(os.environ, OMP_NUM_THREADS='1',
           ASAN_OPTIONS='detect_leaks=1:abort_on_error=0:symbolize=1',
           UBSAN_OPTIONS='print_stacktrace=1', CT_SHARED='/work/shared')

NUM_RE = re.compile(rb'(?<![A-Za-z_0-9.])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?(?![A-Za-z_])')
BADNUMS = [b'nan', b'.nan', b'NaN', b'inf', b'.inf', b'-.inf', b'-inf', b'1e308', b'-1e308', b'1e309',
           b'-1', b'0', b'-0', b'0.0', b'1e-308', b'4.9e-324', b'9223372036854775807',
           b'9223372036854775808', b'-9223372036854775808', b'2147483648', b'4294967296',
           b'99999999999999999999999', b'abc', b'""', b'~', b'null', b'true', b'[]', b'{}',
           b'[1, 2]', b'1.5', b'0x10', b'1e5', b'-1e-9', b'1e-30', b'1e30', b'3', b'1000000']
KEYS = [b'end_time', b'refine', b'cells', b'size', b'origin', b'to', b'radius', b'layers',
        b'spacing', b'E', b'nu', b'rho', b'thickness', b'area', b'stiffness', b'type', b'Istf',
        b'Stfac', b'gap', b'Fric', b'Ifric', b'Ifiltr', b'Xfreq', b'VisS', b'curve', b'where',
        b'value', b'dofs', b'pressure', b'part', b'parts', b'ids', b'surf', b'group', b'kind',
        b'element', b'search', b'every', b'dt_scale', b'threads', b'Tstart', b'Tstop', b'Stmin',
        b'Stmax', b'Gap_max_s', b'Ipen_max', b'C1', b'C5', b'C6', b'tri', b'file', b'length',
        b'rigid_bodies', b'grnd_IDs', b'secondary', b'main', b'format', b'dir', b'Igap0', b'Inacti']
STRS = [b'x < 0', b'z > 1e400', b'x < nan', b'w < 1', b'x <', b'x < 1 and', b'x < 1 and y > 2 and z < 3 and x > -1 and y < 5 and z > -5 and x < 9',
        b'', b'\xff\xfe', b'\xc3\xa9t\xc3\xa9', b'A' * 5000, b'../../etc/passwd', 
        b'/dev/null', b'.', b'nonexistent.rad', b'xyzw', b'zz', b'ball', b'block', b'rod', b'net',
        b'shell', b'brick', b'rigid', b'spring', b'truss', b'bsp', b'direct', b'ascii']


def mutate_numbers(d, rnd, n=1):
    ms = list(NUM_RE.finditer(d))
    if not ms:
        return d, 'nonum'
    tags = []
    for _ in range(n):
        ms = list(NUM_RE.finditer(d))
        if not ms:
            break
        m = rnd.choice(ms)
        r = rnd.choice(BADNUMS)
        ls = d.rfind(b'\n', 0, m.start()) + 1
        km = re.findall(rb'([A-Za-z_]\w*):', d[ls:m.start()])
        d = d[:m.start()] + r + d[m.end():]
        tags.append((km[-1] if km else b'?') + b':num->' + r)
    return d, b';'.join(tags).decode('latin1')


def yaml_mutate(d, rnd):
    lines = d.split(b'\n')
    op = rnd.randrange(22)
    L = len(lines)
    i, j = rnd.randrange(L), rnd.randrange(L)
    tag = ''
    if op == 0:
        del lines[i]; tag = 'delline'
    elif op == 1:
        lines.insert(i, lines[i]); tag = 'dupline'
    elif op == 2:
        lines[i], lines[j] = lines[j], lines[i]; tag = 'swaplines'
    elif op in (3, 4, 5, 6):
        return mutate_numbers(d, rnd, 1 if op != 6 else rnd.randint(2, 4))
    elif op == 7:  # empty value of a key
        ks = list(re.finditer(rb'(\b\w+): ?([^,}\n]*)', d))
        if ks:
            m = rnd.choice(ks)
            d = d[:m.start(2)] + d[m.end(2):]
            return d, 'empty:' + m.group(1).decode('latin1')
    elif op == 8:  # wrong indentation
        lines[i] = (b' ' * rnd.choice([1, 3, 5])) + lines[i] if rnd.random() < .5 else lines[i].lstrip()
        tag = 'indent'
    elif op == 9:
        cut = rnd.randrange(len(d) + 1)
        return d[:cut], 'truncate@%d' % cut
    elif op == 10:  # unknown key inside a flow mapping
        ms = list(re.finditer(rb'\{', d))
        if ms:
            m = rnd.choice(ms)
            k = rnd.choice([b'bogus', b'Stfac', b'E', b'part', b'gap', b'e', b'End_time'])
            d = d[:m.end()] + k + b': 1, ' + d[m.end():]
            return d, 'addkey:' + k.decode()
    elif op == 11:  # scalar -> list / list -> scalar
        ms = list(re.finditer(rb'(\w+): (\[[^\[\]\n]*\]|[^,{}\[\]\n]+)', d))
        if ms:
            m = rnd.choice(ms)
            v = m.group(2)
            if v.startswith(b'['):
                nv = rnd.choice([b'1', b'[]', b'[[1, 2]]', b'{a: 1}', v[1:-1].split(b',')[0]])
            else:
                nv = rnd.choice([b'[' + v + b']', b'[' + v + b', ' + v + b']', b'{x: ' + v + b'}', b'[]'])
            d = d[:m.start(2)] + nv + d[m.end(2):]
            return d, 'shape:' + m.group(1).decode('latin1')
    elif op == 12:  # random bytes
        pos = rnd.randrange(len(d) + 1)
        junk = bytes(rnd.choice([0, 1, 0x7f, 0x80, 0xff, 0xc3, 0xe2, ord('\t'), ord(':'), ord('{'), ord('['), ord('&'), ord('*'), ord('!'), ord('%'), ord('"'), ord("'")]) for _ in range(rnd.randint(1, 4)))
        return d[:pos] + junk + d[pos:], 'bytes'
    elif op == 13:
        return d.replace(b'\n', b'\r\n'), 'crlf'
    elif op == 14:  # long line
        return d + b'\ntitle2: ' + b'x' * rnd.choice([5000, 100000, 1000000]), 'longline'
    elif op == 15:  # set a key's value to a bad string / number
        k = rnd.choice(KEYS)
        ms = list(re.finditer(rb'\b' + k + rb': ?([^,}\n]*)', d))
        if ms:
            m = rnd.choice(ms)
            if rnd.random() < .5:
                v = rnd.choice(BADNUMS)
            else:
                v = b'"' + rnd.choice(STRS) + b'"'
            d = d[:m.start(1)] + v + d[m.end(1):]
            return d, 'set:%s=%r' % (k.decode(), v[:30])
    elif op == 16:  # add a key to the top level or into a flow mapping
        k = rnd.choice(KEYS)
        v = rnd.choice(BADNUMS + [b'"x < 0"', b'[1, 2, 3]', b'[[0, 0], [0, 1]]'])
        ms = list(re.finditer(rb'\{', d))
        if ms:
            m = rnd.choice(ms)
            d = d[:m.end()] + k + b': ' + v + b', ' + d[m.end():]
            return d, 'inskey:%s=%r' % (k.decode(), v[:20])
    elif op == 17:  # YAML specials
        sp = rnd.choice([b'&a ', b'*a', b'!!str ', b'!!binary ', b'<<: ', b'--- ', b'? ', b'|', b'>', b'%YAML 1.1\n', b'...\n', b'---\n'])
        pos = rnd.randrange(len(d) + 1)
        return d[:pos] + sp + d[pos:], 'yamlspecial:%r' % sp
    elif op == 18:  # deep nesting
        n = rnd.choice([50, 70, 200, 100000])
        return d + b'\nextra: ' + b'[' * n + b']' * n, 'deepnest%d' % n
    elif op == 19:  # segment / curve edits: reorder curve points, duplicate point
        ms = list(re.finditer(rb'\[(-?[\d.e+-]+), (-?[\d.e+-]+)\]', d))
        if ms:
            m = rnd.choice(ms)
            c = rnd.randrange(3)
            if c == 0:
                nv = m.group(0) + b', ' + m.group(0)
            elif c == 1:
                nv = b'[' + m.group(2) + b', ' + m.group(1) + b']'
            else:
                nv = b'[-1, ' + m.group(2) + b']'
            d = d[:m.start()] + nv + d[m.end():]
            return d, 'curvept%d' % c
    elif op == 20:  # a whole list entry duplicated (ids repeat)
        ms = [k for k, l in enumerate(lines) if l.lstrip().startswith(b'- ')]
        if ms:
            k = rnd.choice(ms)
            lines.insert(k, lines[k]); tag = 'dupentry'
    elif op == 21:  # cells very large / refine
        k = rnd.choice([b'cells', b'refine', b'layers'])
        v = rnd.choice([b'[100000, 100000, 100000]', b'[0]', b'[-3, 2]', b'[1, 1, 1, 1]', b'100000', b'[3000000000]', b'[65536, 65536]', b'[2000, 2000]'])
        ms = list(re.finditer(rb'\b' + k + rb': ?([^,}\n]*\]?|\[[^\]]*\])', d))
        if ms:
            m = rnd.choice(ms)
            d = d[:m.start(1)] + v + d[m.end(1):]
            return d, 'big:%s=%s' % (k.decode(), v.decode())
    if not tag:
        return mutate_numbers(d, rnd)
    return b'\n'.join(lines), tag


def deck_mutate(d, rnd):
    lines = d.split(b'\n')
    L = len(lines)
    i = rnd.randrange(L)
    op = rnd.randrange(16)
    data = [k for k, l in enumerate(lines) if l and not l.startswith((b'/', b'#'))]
    kws = [k for k, l in enumerate(lines) if l.startswith(b'/')]
    if op == 0:
        del lines[i]; return b'\n'.join(lines), 'd:delline'
    if op == 1:
        lines.insert(i, lines[i]); return b'\n'.join(lines), 'd:dupline'
    if op == 2 and data:  # truncate a card
        k = rnd.choice(data); lines[k] = lines[k][:rnd.randrange(len(lines[k]) + 1)]
        return b'\n'.join(lines), 'd:truncard'
    if op in (3, 4) and data:  # corrupt a field (fixed width)
        k = rnd.choice(data); l = lines[k]
        w = 20 if (len(l) > 30 and b'.' in l) else 10
        f = rnd.randrange(max(1, (len(l) + w - 1) // w))
        v = rnd.choice(BADNUMS + [b'NaN', b'Inf', b'-Infinity', b'1.5+400', b'1.D999', b'1e', b'--1', b'1.2.3', b'  ', b'0', b'-5', b'99999', b'1e10', b'9999999999', b'12345678901234567890', b'\x00', b'\xff', b'#'])
        seg = v[:w].rjust(w) if rnd.random() < .7 else v[:w].ljust(w)
        start = f * w if w == 10 or f == 0 else 10 + (f - 1) * 20
        if w == 20 and f == 0:
            seg = v[:10].rjust(10); nl = l[:0] + seg + l[10:]
        else:
            nl = l[:start] + seg + l[start + len(seg):]
        lines[k] = nl
        return b'\n'.join(lines), 'd:field->%r' % v[:20]
    if op == 5 and data:  # bad node id (refer to unknown / repeat)
        k = rnd.choice(data); l = lines[k]
        if len(l) >= 30:
            fs = [l[x:x + 10] for x in range(0, len(l), 10)]
            c = rnd.randrange(3)
            if c == 0 and len(fs) > 2:
                fs[2] = fs[1]  # repeated node in element
            elif c == 1:
                fs[rnd.randrange(len(fs))] = b'%10d' % rnd.choice([0, -1, 999999, 2**31, 2**63 - 1])
            elif len(fs) > 4:
                fs[3] = fs[1]; fs[4] = fs[2]  # degenerate
            lines[k] = b''.join(fs)
            return b'\n'.join(lines), 'd:ids%d' % c
    if op == 6 and kws:  # corrupt keyword
        k = rnd.choice(kws)
        lines[k] = rnd.choice([lines[k] + b'/X', lines[k].rsplit(b'/', 1)[0] + b'/-1', lines[k].rsplit(b'/', 1)[0] + b'/abc',
                               lines[k].rsplit(b'/', 1)[0] + b'/99999999999999999999', lines[k].lower(), lines[k][:3],
                               lines[k].rsplit(b'/', 1)[0] + b'/', b'/', lines[k] + b' ' * 5000, lines[k].rsplit(b'/', 1)[0] + b'/0'])
        return b'\n'.join(lines), 'd:kw'
    if op == 7:
        cut = rnd.randrange(len(d) + 1); return d[:cut], 'd:truncate'
    if op == 8:
        return d.replace(b'\n', b'\r\n'), 'd:crlf'
    if op == 9:
        lines.insert(i, rnd.choice([b'#include missing.inc', b'/END', b'/NODE', b'/SHELL/1', b'/BRICK/1', b'/SH3N/1', b'/PART/1', b'/SURF/PART/9', b'/GRNOD/NODE/2', b'/GRSHEL/SHEL/20', b'/SURF/GRSHEL/9', b'/GRNOD/GRSHEL/5', b'/TITLE', b'/BEGIN', b'/SURF/PART/EXT/7']))
        return b'\n'.join(lines), 'd:inskw'
    if op == 10:
        lines.insert(i, b'x' * rnd.choice([4095, 4096, 4097, 100000])); return b'\n'.join(lines), 'd:longline'
    if op == 11:
        pos = rnd.randrange(len(d) + 1)
        return d[:pos] + bytes(rnd.randrange(256) for _ in range(rnd.randint(1, 3))) + d[pos:], 'd:bytes'
    if op == 12 and data:  # make degenerate geometry: copy node coords onto another node
        nodes = [k for k in data if len(lines[k]) >= 60 and b'.' in lines[k] or len(lines[k]) >= 60]
        if len(nodes) >= 2:
            a, b = rnd.sample(nodes, 2)
            lines[b] = lines[b][:10] + lines[a][10:]
            return b'\n'.join(lines), 'd:samecoord'
    if op == 13 and kws:  # delete a whole block
        k = rnd.choice(kws)
        e = k + 1
        while e < L and not lines[e].startswith(b'/'):
            e += 1
        del lines[k:e]
        return b'\n'.join(lines), 'd:delblock'
    if op == 14 and data:  # tabs / no width
        k = rnd.choice(data); lines[k] = b'\t'.join(lines[k].split()) if rnd.random() < .5 else b' '.join(lines[k].split())
        return b'\n'.join(lines), 'd:fieldsplit'
    if op == 15:
        return mutate_numbers(d, rnd, rnd.randint(1, 3))
    return mutate_numbers(d, rnd)


SAN_RE = re.compile(r'#(\d+) 0x[0-9a-f]+ in (\S+) (\S+)')


def top_frame(err):
    frames = SAN_RE.findall(err)
    for _, fn, loc in frames:
        if '/driver/' in loc or '/kernels/' in loc or '/src/' in loc:
            return fn + ' ' + loc.split('/wt/')[-1]
    if frames:
        return frames[0][1] + ' ' + frames[0][2].split('/')[-1]
    m = re.search(r'(\S+:\d+:\d+): runtime error: (.*)', err)
    if m:
        return m.group(1).split('/wt/')[-1]
    return '?'


def tags_list(tag):
    return [t.strip() for t in tag.split('|')]


def classify(rc, out, err, tag, scene_name, deck_name, outdir):
    kinds = []
    if rc == 124:
        kinds.append(('timeout', ''))
    if 'ERROR: AddressSanitizer' in err:
        m = re.search(r'ERROR: AddressSanitizer: (\S+)', err)
        kinds.append(('asan-' + (m.group(1) if m else '?'), top_frame(err)))
    if 'ERROR: LeakSanitizer' in err:
        kinds.append(('leak', top_frame(err.split('ERROR: LeakSanitizer')[1])))
    if 'runtime error:' in err:
        m = re.search(r'(\S+): runtime error: ([^\n]*)', err)
        msg = re.sub(r'-?\d[\d.e+-]*', 'N', m.group(2))[:80] if m else ''
        kinds.append(('ubsan', (m.group(1).split('/wt/')[-1] if m else '?') + ' ' + msg))
    if rc < 0 or (rc >= 128 and rc != 124):
        kinds.append(('signal', str(rc)))
    if kinds:
        return kinds
    if rc == 2:
        # error messages must name the file and a line
        lines = [l for l in err.strip().split('\n') if l and 'invalid scene' not in l and 'more errors' not in l]
        for l in lines[:3]:
            l = re.sub(r'^contact \w+: ', '', l)
            if not re.match(r'^\S+:\d+: ', l):
                kinds.append(('msg-noline', re.sub(r'\d+', 'N', l)[:100]))
                break
            if 'cannot load the Radioss deck' in l and not re.search(r'\.rad:\d+: ', l):
                kinds.append(('msg-deck-noline', re.sub(r'\d+', 'N', l)[:100]))
                break
        return kinds
    if rc == 0:
        # silent garbage: nan/inf in outputs
        try:
            s = open(os.path.join(outdir, 'summary.json'), 'rb').read()
            if re.search(rb'\b(nan|inf|NaN|Infinity)\b', s, re.I):
                kinds.append(('rc0-nan-summary', tag.split(':')[0].split('->')[0]))
        except OSError:
            pass
        try:
            h = open(os.path.join(outdir, 'history.csv'), 'rb').read()
            if re.search(rb'\b(nan|inf)\b', h, re.I):
                kinds.append(('rc0-nan-history', tag.split(':')[0].split('->')[0]))
        except OSError:
            pass
        for t in tags_list(tag):
            if t.startswith('cli:'):
                continue
            if re.search(r'nan|inf|1e30[89]|4\.9e-324|1e-308', t, re.I) and not re.match(r'(title|name|\?)[:=]', t):
                kinds.append(('rc0-suspicious', re.sub(r"num->.*|=.*", '', t)))
        return kinds
    if rc in (1, 3, 4, 5):
        kinds.append(('rc%d' % rc, re.sub(r'\d+', 'N', (err.strip().split('\n') or [''])[0])[:100]))
        return kinds
    kinds.append(('rc-other', str(rc)))
    return kinds


def main():
    budget = float(sys.argv[1]) if len(sys.argv) > 1 else 3000
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    rnd = random.Random(seed)
    os.makedirs(FIND, exist_ok=True)
    os.makedirs('/tmp/fuzz/rc0nan', exist_ok=True)
    scenes = sorted(f for f in os.listdir(SEEDS) if f.endswith('.yaml'))
    deck_scene = {'s_int357.yaml': 'int357.rad', 's_tri.yaml': 'tri.rad', 's_brick.yaml': 'brick.rad'}
    seen = {}
    t0 = time.time()
    n = 0
    logf = open(LOG, 'a')
    while time.time() - t0 < budget:
        n += 1
        sc = rnd.choice(scenes)
        cdir = os.path.join(WORK, 'cur')
        shutil.rmtree(cdir, ignore_errors=True)
        os.makedirs(cdir)
        for dk in DECKS:
            shutil.copy(os.path.join(SEEDS, dk), cdir)
        sd = open(os.path.join(SEEDS, sc), 'rb').read()
        tags = []
        deck = deck_scene.get(sc)
        if deck and rnd.random() < 0.6:
            dd = open(os.path.join(SEEDS, deck), 'rb').read()
            for _ in range(rnd.choice([1, 1, 1, 2, 3])):
                dd, t = deck_mutate(dd, rnd); tags.append(t)
            open(os.path.join(cdir, deck), 'wb').write(dd)
        else:
            for _ in range(rnd.choice([1, 1, 1, 2, 3])):
                sd, t = yaml_mutate(sd, rnd); tags.append(t)
        open(os.path.join(cdir, sc), 'wb').write(sd)
        outdir = os.path.join(WORK, 'out')
        shutil.rmtree(outdir, ignore_errors=True)
        extra = []
        if rnd.random() < 0.05:
            extra = rnd.choice([['--end', 'nan'], ['--end', '-1'], ['--end', '1e308'], ['--refine', '0'], ['--refine', '1001'],
                                ['--refine', 'abc'], ['--dt-scale', 'nan'], ['--dt-scale', '0'], ['--dt-scale', 'inf'],
                                ['--threads', '-1'], ['--threads', '99999999999'], ['--search', 'foo'], ['--end'], ['--out'],
                                ['--dt-scale', '-1'], ['--end', '1e-300'], ['--refine', '2']])
            tags.append('cli:' + ' '.join(extra))
        if rnd.random() < 0.15:
            cmd = [BIN, 'check', sc]
        else:
            cmd = [BIN, 'run', sc, '--out', outdir, '--quiet'] + extra
        try:
            p = subprocess.run(['timeout', '20'] + cmd, cwd=cdir, env=ENV, capture_output=True)
            rc = p.returncode
            out, err = p.stdout.decode('latin1'), p.stderr.decode('latin1')
        except Exception as e:
            rc, out, err = -999, '', str(e)
        if rnd.random() < 0.05 and 'cli:' in ''.join(tags[-1:]) and cmd[1] == 'check':
            pass
        tag = ' | '.join(tags)
        kinds = classify(rc, out, err, tag, sc, deck, outdir)
        rec = {'n': n, 'scene': sc, 'tags': tag, 'cmd': cmd[1], 'rc': rc, 'kinds': kinds,
               'err': err[:300]}
        logf.write(json.dumps(rec) + '\n')
        if rc == 0 and cmd[1] == 'run' and re.search(r'nan|inf', tag, re.I):
            d0 = os.path.join('/tmp/fuzz/rc0nan', '%d-%d' % (seed, n))
            if len(os.listdir('/tmp/fuzz/rc0nan')) < 400:
                shutil.copytree(cdir, d0)
                open(os.path.join(d0, 'info.txt'), 'w').write(tag + '\n' + err[:2000])
        for k in kinds:
            key = k[0] + '|' + k[1]
            if key not in seen:
                seen[key] = 0
                h = hashlib.md5(key.encode()).hexdigest()[:8]
                dst = os.path.join(FIND, '%s-%s' % (k[0], h))
                if not os.path.exists(dst):
                    shutil.copytree(cdir, dst)
                    open(os.path.join(dst, 'info.txt'), 'w').write(
                        'key: %s\ncmd: %s\nrc: %d\ntags: %s\n--- stdout\n%s\n--- stderr\n%s\n' % (
                            key, ' '.join(cmd), rc, tag, out[:3000], err[:20000]))
                print('NEW', n, key, '<-', sc, tag, flush=True)
            seen[key] += 1
        if n % 200 == 0:
            print('cases', n, 'elapsed %.0f' % (time.time() - t0), 'distinct', len(seen), flush=True)
    print('DONE cases', n, flush=True)
    json.dump(seen, open('/tmp/fuzz/seen-%d.json' % seed, 'w'), indent=1)


if __name__ == '__main__':
    main()
