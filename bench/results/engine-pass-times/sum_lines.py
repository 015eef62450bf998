# The frame lines of examples/engine_backend: each frame's passes summed against its printed frame time.
import sys, re
for line in sys.stdin:
    m = re.match(r'(frame-\d+): blurred in ([\d.]+) ms \((.*)\)', line)
    if not m: continue
    passes = m.group(3).split(', ')
    total = sum(float(p.split()[-1]) for p in passes)
    print(f"{m.group(1)} frame {float(m.group(2)):.2f} ms, passes {len(passes)} named, sum {total:.2f} ms ({100*total/float(m.group(2)):.1f}%)")
