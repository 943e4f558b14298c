import subprocess, re, statistics, sys, json
exes = {'before': sys.argv[1],
        'after': sys.argv[2]}
configs = [('full', []), ('primary', ['--max-depth', '0'])]
backends = ['cpu', 'simd', 'opencl', 'glsl', 'glsl-compute']
runs = 7
res = {}
for be in backends:
    for cname, extra in configs:
        for r in range(runs):
            for tag in (['before', 'after'] if r % 2 == 0 else ['after', 'before']):
                cmd = [exes[tag], 'render', 'builtin:thesis-b', '--backend', be, '--size', '512x384',
                       '--bench-frames', '9', '--quiet', '--out', '/dev/null'] + extra
                out = subprocess.run(cmd, capture_output=True, text=True).stdout
                m = re.search(r'after the first: median ([0-9.]+) ms', out)
                if not m:
                    print('no median', tag, be, cname, out[-300:], file=sys.stderr); continue
                res.setdefault((be, cname, tag), []).append(float(m.group(1)))
        b = statistics.median(res[(be, cname, 'before')]); a = statistics.median(res[(be, cname, 'after')])
        print(f'{be:13s} {cname:8s} before {b:8.2f} ms  after {a:8.2f} ms  after/before {a/b:.3f}  runs {res[(be,cname,"before")]} {res[(be,cname,"after")]}', flush=True)
