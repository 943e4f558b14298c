# Sums log.tsv (profile.sh) by test suite: seconds, tests and new kernels per backend; the argument: how many to list.
import re, collections, sys
rows=[]
for line in open(__import__('os').path.join(__import__('os').path.dirname(__file__) or '.', 'log.tsv')):
    f=line.rstrip('\n').split('\t')
    if len(f)<5: continue
    name,sec,rc,before,after=f
    def parse(s):
        d={}
        for m in re.finditer(r'(\d+) ([\w-]+)', s): d[m.group(2)]=int(m.group(1))
        return d
    b,a=parse(before),parse(after)
    new={k:a.get(k,0)-b.get(k,0) for k in a}
    rows.append((name,float(sec),rc,new))
print('tests',len(rows),'sum s',sum(r[1] for r in rows))
fails=[r for r in rows if r[2]!='0']
print('nonzero rc', [(r[0],r[2]) for r in fails][:10])
tot=collections.Counter()
for r in rows:
    for k,v in r[3].items(): tot[k]+=v
print('new kernels', dict(tot))
# per suite (strip parameter) 
def suite(n):
    n=re.sub(r'\s+#.*','',n)
    m=re.match(r'(?:\w+/)?(\w+)\.(\w+)/(\w+)',n)
    if m: return m.group(1)+'.'+m.group(2), m.group(3)
    return n, ''
by=collections.defaultdict(lambda:[0.0,0,collections.Counter()])
for r in rows:
    s,_=suite(r[0]); by[s][0]+=r[1]; by[s][1]+=1; by[s][2].update(r[3])
top=int(sys.argv[1]) if len(sys.argv)>1 else 50
for s,(t,n,k) in sorted(by.items(), key=lambda x:-x[1][0])[:top]:
    print(f'{t:7.1f} {n:3d} {s[:80]:80s} {dict(k)}')
