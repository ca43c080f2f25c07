#!/usr/bin/env python3
"""Train the learned one-step MAPF policy by imitating LaCAM, export it for the C++ planner.

Three steps, all from this one command (issue 6):
  1. dump   `rtlacam-policy dump` runs our full-horizon LaCAM (with swap) on MovingAI
            instances and writes (observation, expert next action) pairs (policy/dump_file.hpp);
  2. train  an MLP (policy/model.hpp) with PyTorch, cross-entropy, Adam, fixed seed;
  3. export the weights file (policy/weights_file.hpp) and a golden file of inputs and
            PyTorch logits (policy/golden_file.hpp) that the C++ tests compare Eigen against.

Needs Debian's PyTorch (apt-get install -y python3-torch) and numpy; run it with
/usr/bin/python3 (a pyenv `python3` on PATH does not see Debian packages). Outside CI only.

  /usr/bin/python3 scripts/train_policy.py --bin build-policy/apps/rtlacam-policy

The committed model (policy/models/) was made with exactly that command (defaults below:
random-32-32-20, scens 1..20 -- 21..25 are kept for evaluation --, seed 0).
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import time

import numpy as np
import torch
from torch import nn

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NUM_ACTIONS = 5
ACTION_NAMES = ["stay", "up", "down", "left", "right"]


def parse_range(s):
    """'1-20' or '1 2 5' -> list of ints."""
    out = []
    for part in s.replace(",", " ").split():
        if "-" in part:
            a, b = part.split("-")
            out += list(range(int(a), int(b) + 1))
        else:
            out.append(int(part))
    return out


def run_dump(args, dump_path):
    scens = [os.path.join(ROOT, "data/movingai", f"{args.map}-random-{k}.scen") for k in parse_range(args.scens)]
    cmd = [args.bin, "dump", "--map", os.path.join(ROOT, "data/movingai", args.map + ".map"), "--scen", *scens,
           "-N", *[str(n) for n in parse_range(args.agents)], "--keep", str(args.keep), "--radius", str(args.radius),
           "--seed", str(args.seed), "--timeout-s", str(args.dump_timeout_s), "--out", dump_path]
    print("dump:", " ".join(os.path.relpath(c, ROOT) if c.startswith(ROOT) else c for c in cmd), flush=True)
    t0 = time.time()
    subprocess.run(cmd, check=True, stderr=subprocess.DEVNULL if args.quiet else None)
    print(f"dump: {time.time() - t0:.1f} s", flush=True)


def load_dump(path):
    """-> (x float32 [n, features], action int64 [n], flags uint8 [n], radius)."""
    with open(path, "rb") as f:
        head = f.read(8 + 4 * 4)
        magic, version, radius, channels, features = struct.unpack("<8s4I", head)
        if magic != b"RTLPDUMP" or version != 1:
            sys.exit(f"{path}: not a version-1 policy dump file")
        scale = np.frombuffer(f.read(4 * channels), dtype="<f4")
        (count,) = struct.unpack("<Q", f.read(8))
        rec = np.dtype([("q", "i1", (features,)), ("action", "u1"), ("flags", "u1")])
        data = np.fromfile(f, dtype=rec, count=count)
    if len(data) != count:
        sys.exit(f"{path}: truncated ({len(data)} of {count} records)")
    area = features // channels
    # x = q / scale[channel], exactly as the C++ observation builder computes it (a division)
    x = data["q"].astype(np.float32).reshape(count, channels, area) / scale.astype(np.float32)[None, :, None]
    return x.reshape(count, features), data["action"].astype(np.int64), data["flags"], radius


# The 8 symmetries of the square window (transpose?, flip columns?, flip rows?) and what
# each does to the actions (stay, up, down, left, right): random maps look the same in every
# orientation, so each batch is shown in a random one (8x the data for free).
TRANSPOSE = [0, 3, 4, 1, 2]   # up <-> left, down <-> right
FLIP_X = [0, 1, 2, 4, 3]      # left <-> right
FLIP_Y = [0, 2, 1, 3, 4]      # up <-> down


def augment(xb, yb, k, channels, window):
    """Symmetry k (0..7) applied to a batch of flat observations and their actions."""
    if k == 0:
        return xb, yb
    v = xb.view(-1, channels, window, window)  # [c][wy][wx]
    perm = torch.arange(NUM_ACTIONS)
    if k & 1:
        v = v.transpose(2, 3)
        perm = torch.tensor(TRANSPOSE)[perm]
    if k & 2:
        v = v.flip(3)
        perm = torch.tensor(FLIP_X)[perm]
    if k & 4:
        v = v.flip(2)
        perm = torch.tensor(FLIP_Y)[perm]
    return v.reshape(xb.shape[0], -1), perm[yb]


def make_model(features, hidden):
    layers, width = [], features
    for h in hidden:
        layers += [nn.Linear(width, h), nn.ReLU()]
        width = h
    layers.append(nn.Linear(width, NUM_ACTIONS))
    return nn.Sequential(*layers)


def linears(model):
    return [m for m in model if isinstance(m, nn.Linear)]


def export_weights(model, radius, path):
    with open(path, "wb") as f:
        lin = linears(model)
        f.write(struct.pack("<8s5I", b"RTLPOLCY", 1, radius, 4, NUM_ACTIONS, len(lin)))
        for l in lin:
            w = l.weight.detach().numpy().astype("<f4")  # out x in, row-major: nn.Linear's layout
            b = l.bias.detach().numpy().astype("<f4")
            f.write(struct.pack("<2I", w.shape[0], w.shape[1]))
            f.write(np.ascontiguousarray(w).tobytes())
            f.write(b.tobytes())


def export_golden(model, x, path):
    with torch.no_grad():
        logits = model(torch.from_numpy(x)).numpy().astype("<f4")
    with open(path, "wb") as f:
        f.write(struct.pack("<8s4I", b"RTLGOLDN", 1, x.shape[0], x.shape[1], logits.shape[1]))
        f.write(np.ascontiguousarray(x, dtype="<f4").tobytes())
        f.write(np.ascontiguousarray(logits).tobytes())


def accuracy(model, x, y, batch=8192):
    model.eval()
    correct = 0
    with torch.no_grad():
        for k in range(0, len(x), batch):
            correct += (model(x[k:k + batch]).argmax(1) == y[k:k + batch]).sum().item()
    model.train()
    return correct / max(1, len(x))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(ROOT, "build/apps/rtlacam-policy"), help="rtlacam-policy binary")
    ap.add_argument("--map", default="random-32-32-20", help="map name under data/movingai")
    ap.add_argument("--scens", default="1-20", help="training scens (21..25 are for evaluation)")
    ap.add_argument("--agents", default="10 25 50 100 150 200 250 300 350", help="agent counts per scen")
    ap.add_argument("--keep", type=float, default=0.2, help="fraction of (agent, step) samples dumped")
    ap.add_argument("--dump-timeout-s", type=float, default=10.0, help="LaCAM limit per instance")
    ap.add_argument("--radius", type=int, default=4, help="observation radius (window 2r+1)")
    ap.add_argument("--hidden", default="128 64", help="hidden layer widths")
    ap.add_argument("--epochs", type=int, default=8)
    ap.add_argument("--batch", type=int, default=256)
    ap.add_argument("--lr", type=float, default=1e-3)
    ap.add_argument("--goal-stay-keep", type=float, default=0.3,
                    help="fraction kept of the samples 'on the goal, stays' (they dominate late steps)")
    ap.add_argument("--no-augment", dest="augment", action="store_false",
                    help="do not show batches in random rotations/reflections of the window")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--threads", type=int, default=1, help="torch CPU threads (the machine is shared)")
    ap.add_argument("--work-dir", default=os.path.join(ROOT, "out/policy_train"), help="dump file goes here")
    ap.add_argument("--reuse-dump", action="store_true", help="train on an existing dump in --work-dir")
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "policy/models"))
    ap.add_argument("--name", default="random-32-32-20", help="writes <name>.bin, <name>.golden, <name>.json")
    ap.add_argument("--golden-n", type=int, default=256, help="samples in the golden file")
    ap.add_argument("--quiet", action="store_true", help="hide the per-instance dump log")
    args = ap.parse_args()

    torch.manual_seed(args.seed)
    torch.set_num_threads(args.threads)
    rng = np.random.default_rng(args.seed)
    os.makedirs(args.work_dir, exist_ok=True)
    os.makedirs(args.out_dir, exist_ok=True)
    dump_path = os.path.join(args.work_dir, "dump.bin")
    if not (args.reuse_dump and os.path.exists(dump_path)):
        run_dump(args, dump_path)

    x, y, flags, radius = load_dump(dump_path)
    goal_stay = ((flags & 1) == 1) & (y == 0)
    keep = ~goal_stay | (rng.random(len(y)) < args.goal_stay_keep)
    x, y = x[keep], y[keep]
    n = len(y)
    counts = np.bincount(y, minlength=NUM_ACTIONS)
    print(f"data: {n} samples ({int(goal_stay.sum())} on-goal stays before thinning), radius {radius}, "
          f"{x.shape[1]} features; actions " + ", ".join(f"{a} {c / n:.1%}" for a, c in zip(ACTION_NAMES, counts)),
          flush=True)

    perm = rng.permutation(n)
    n_val = max(args.golden_n, n // 10)
    val, train = perm[:n_val], perm[n_val:]
    xt, yt = torch.from_numpy(x[train]), torch.from_numpy(y[train])
    xv, yv = torch.from_numpy(x[val]), torch.from_numpy(y[val])

    hidden = [int(h) for h in args.hidden.split()]
    model = make_model(x.shape[1], hidden)
    opt = torch.optim.Adam(model.parameters(), lr=args.lr)
    sched = torch.optim.lr_scheduler.CosineAnnealingLR(opt, T_max=args.epochs)
    loss_fn = nn.CrossEntropyLoss()
    gen = torch.Generator().manual_seed(args.seed)
    t0 = time.time()
    for epoch in range(args.epochs):
        order = torch.randperm(len(yt), generator=gen)
        total = 0.0
        for k in range(0, len(order), args.batch):
            idx = order[k:k + args.batch]
            xb, yb = xt[idx], yt[idx]
            if args.augment:
                xb, yb = augment(xb, yb, int(torch.randint(8, (1,), generator=gen)), 4, 2 * radius + 1)
            opt.zero_grad()
            loss = loss_fn(model(xb), yb)
            loss.backward()
            opt.step()
            total += loss.item() * len(idx)
        sched.step()
        print(f"epoch {epoch + 1}/{args.epochs}: train loss {total / len(yt):.4f}, "
              f"val accuracy {accuracy(model, xv, yv):.4f} ({time.time() - t0:.0f} s)", flush=True)

    model.eval()
    weights = os.path.join(args.out_dir, args.name + ".bin")
    golden = os.path.join(args.out_dir, args.name + ".golden")
    export_weights(model, radius, weights)
    export_golden(model, x[val[:args.golden_n]], golden)
    meta = {
        "command": "/usr/bin/python3 " + " ".join([os.path.relpath(sys.argv[0], ROOT)] + sys.argv[1:]),
        "args": {k: v for k, v in vars(args).items() if k not in ("bin", "work_dir", "out_dir")},
        "samples": n, "train": len(train), "val": len(val),
        "action_fractions": {a: round(float(c / n), 4) for a, c in zip(ACTION_NAMES, counts)},
        "val_accuracy": round(accuracy(model, xv, yv), 4),
        "train_accuracy": round(accuracy(model, xt[:50000], yt[:50000]), 4),
        "parameters": sum(p.numel() for p in model.parameters()),
        "torch": torch.__version__, "train_s": round(time.time() - t0, 1),
    }
    with open(os.path.join(args.out_dir, args.name + ".json"), "w") as f:
        json.dump(meta, f, indent=2)
        f.write("\n")
    print(json.dumps(meta, indent=2))
    print(f"wrote {os.path.relpath(weights, ROOT)} ({os.path.getsize(weights)} bytes) and {os.path.relpath(golden, ROOT)}")


if __name__ == "__main__":
    main()
