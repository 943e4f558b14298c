# Sums docs/benchmarks/2026-12-03-test-kernels/log.tsv (profile.sh) by family of tests: count, seconds, new kernels per backend.
import re, collections
rt_suites=set('MegakernelLoopRender Render KnobsOnBackend LightBufferRender ShaderRender DynamicRender HardCases FilmTest GridTraversal Window Strategies Shaders Grid BadInput Scene Cli Distributed KilledWorker'.split())
fam=collections.defaultdict(lambda:[0.0,0,collections.Counter()])
for line in open(__import__('os').path.join(__import__('os').path.dirname(__file__) or '.', 'log.tsv')):
    f=line.rstrip('\n').split('\t')
    if len(f)<5: continue
    name,sec=f[0],float(f[1])
    def parse(s): return {m.group(2):int(m.group(1)) for m in re.finditer(r'(\d+) ([\w-]+)', s)}
    b,a=parse(f[3]),parse(f[4]); new={k:a.get(k,0)-b.get(k,0) for k in a}
    m=re.match(r'(?:(\w+)/)?(\w+)\.',name)
    suite=m.group(2) if m else name
    if name.startswith('bench.'): k='benchmark smoke runs'
    elif name.startswith('example.'): k='examples'
    elif name.startswith('conformance.') or 'Conformance' in name: k='conformance'
    elif 'Differential' in name: k='differential'
    elif m and m.group(1)=='Backends' and suite in rt_suites: k='ray tracer, per backend'
    elif m and m.group(1)=='Backends': k='backend suite'
    elif suite in ('Cli','Distributed','KilledWorker') : k='rill-trace CLI and MPI'
    else: k='other (DSL, host-only ray tracer, tools)'
    fam[k][0]+=sec; fam[k][1]+=1; fam[k][2].update(new)
for k,(t,n,c) in sorted(fam.items(), key=lambda x:-x[1][0]):
    print(f'| {k} | {n} | {t:.0f} | {c["cpu"]} | {c["simd"]} | {c["opencl"]} | {c["glsl"]} | {c["glsl-compute"]} |')
