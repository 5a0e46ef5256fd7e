//! `examples/slurm/` on a real Slurm cluster: the test starts a single-node cluster on this
//! machine (Debian's slurmctld, slurmd and munge, from `.ci/install-packages`), submits a
//! small benchmark as a job array of shards with its merge job, and checks the merged
//! database against an unsharded run of the same grid.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The daemons of a one-node cluster in a folder of its own; stopped when dropped.
struct Cluster {
    dir: PathBuf,
    conf: PathBuf,
    daemons: Vec<Child>,
}

impl Drop for Cluster {
    fn drop(&mut self) {
        for daemon in &mut self.daemons {
            let _ = daemon.kill();
            let _ = daemon.wait();
        }
    }
}

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

fn output(command: &mut Command) -> String {
    let out = command
        .output()
        .unwrap_or_else(|e| panic!("{command:?}: {e} (install with bash .ci/install-packages)"));
    assert!(
        out.status.success(),
        "{command:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).trim().to_string()
}

fn daemon(program: &str, args: &[&str], log: &Path) -> Child {
    Command::new(program)
        .args(args)
        .stdout(std::fs::File::create(log).unwrap())
        .stderr(Stdio::from(
            std::fs::File::options().append(true).open(log).unwrap(),
        ))
        .spawn()
        .unwrap_or_else(|e| panic!("{program}: {e} (install with bash .ci/install-packages)"))
}

fn wait_for(what: &str, seconds: u64, mut done: impl FnMut() -> bool, logs: &Path) {
    let started = Instant::now();
    while !done() {
        if started.elapsed() > Duration::from_secs(seconds) {
            let mut text = String::new();
            for entry in std::fs::read_dir(logs).unwrap().flatten() {
                if entry
                    .path()
                    .extension()
                    .is_some_and(|e| e == "log" || e == "out")
                {
                    text += &format!(
                        "--- {}\n{}\n",
                        entry.path().display(),
                        std::fs::read_to_string(entry.path()).unwrap_or_default()
                    );
                }
            }
            panic!("{what}: not within {seconds} s\n{text}");
        }
        std::thread::sleep(Duration::from_millis(200));
    }
}

impl Cluster {
    fn start(dir: &Path) -> Cluster {
        let _ = std::fs::remove_dir_all(dir);
        for sub in ["state", "spool"] {
            std::fs::create_dir_all(dir.join(sub)).unwrap();
        }
        // munge: a key of our own, a socket in the folder.
        let key = dir.join("munge.key");
        let bytes: Vec<u8> = (0..1024u32)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8 ^ std::process::id() as u8)
            .collect();
        std::fs::write(&key, bytes).unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&key, std::fs::Permissions::from_mode(0o600)).unwrap();
        let socket = dir.join("munge.sock");
        let path = |p: &Path| p.to_str().unwrap().to_string();
        let munged = daemon(
            "munged",
            &[
                "-F",
                "-f",
                &format!("--socket={}", path(&socket)),
                &format!("--key-file={}", path(&key)),
                &format!("--pid-file={}", path(&dir.join("munged.pid"))),
                &format!("--log-file={}", path(&dir.join("munged.log"))),
                &format!("--seed-file={}", path(&dir.join("munged.seed"))),
            ],
            &dir.join("munged.out"),
        );
        let mut cluster = Cluster {
            dir: dir.to_path_buf(),
            conf: dir.join("slurm.conf"),
            daemons: vec![munged],
        };
        wait_for("munged's socket", 20, || socket.exists(), dir);

        let user = output(Command::new("id").arg("-un"));
        // The controller must run on the host it is configured for; the node may have a
        // name of its own (slurmd -N).
        let host = output(Command::new("hostname").arg("-s"));
        let node = "pushplan-node";
        let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
        let d = path(dir);
        let conf = format!(
            "ClusterName=pushplantest\n\
             SlurmctldHost={host}(127.0.0.1)\nMailProg=/bin/true\n\
             SlurmUser={user}\nSlurmdUser={user}\n\
             AuthType=auth/munge\nCredType=cred/munge\nAuthInfo=socket={socket}\n\
             StateSaveLocation={d}/state\nSlurmdSpoolDir={d}/spool\n\
             SlurmctldPidFile={d}/slurmctld.pid\nSlurmdPidFile={d}/slurmd.pid\n\
             SlurmctldLogFile={d}/slurmctld.log\nSlurmdLogFile={d}/slurmd.log\n\
             SlurmctldPort={}\nSlurmdPort={}\n\
             ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n\
             SelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n\
             SchedulerType=sched/backfill\nReturnToService=2\nMpiDefault=none\n\
             JobCompType=jobcomp/none\nAccountingStorageType=accounting_storage/none\n\
             JobAcctGatherType=jobacct_gather/none\n\
             NodeName={node} NodeAddr=127.0.0.1 CPUs={cpus} State=UNKNOWN\n\
             PartitionName=test Nodes={node} Default=YES MaxTime=INFINITE State=UP\n",
            free_port(),
            free_port(),
            socket = path(&socket),
        );
        std::fs::write(&cluster.conf, conf).unwrap();
        let conf = path(&cluster.conf);
        cluster.daemons.push(daemon(
            "slurmctld",
            &["-D", "-f", &conf],
            &dir.join("slurmctld.out"),
        ));
        cluster.daemons.push(daemon(
            "slurmd",
            &["-D", "-f", &conf, "-N", node],
            &dir.join("slurmd.out"),
        ));
        wait_for(
            "the node to be idle",
            60,
            || {
                cluster
                    .command("sinfo")
                    .args(["-h", "-o", "%T"])
                    .output()
                    .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "idle")
            },
            dir,
        );
        cluster
    }

    /// A Slurm client command for this cluster.
    fn command(&self, program: &str) -> Command {
        let mut command = Command::new(program);
        command.env("SLURM_CONF", &self.conf);
        command
    }
}

#[test]
fn the_slurm_example_runs_shards_and_merges_them_as_one_benchmark() {
    let base = std::env::temp_dir().join(format!("pushplan-slurm-{}", std::process::id()));
    let cluster = Cluster::start(&base.join("cluster"));
    let out = base.join("results");
    let pushplan = env!("CARGO_BIN_EXE_pushplan");
    let scenes = "scenes/benchmark/scene_00.yaml scenes/benchmark/scene_05.yaml";
    let settings = [
        ("PLANNERS", "pcrrt,kpiece"),
        ("RUNS", "3"),
        ("TIME", "1"),
        ("SEED", "7"),
        ("SHORTCUT", "0"),
    ];
    let ids = output(
        cluster
            .command("examples/slurm/submit.sh")
            .arg(format!("--output={}/task-%A_%a.out", cluster.dir.display()))
            .env("OUT", &out)
            .env("SHARDS", "3")
            .env("PUSHPLAN", pushplan)
            .env("SCENES", scenes)
            .envs(settings),
    );
    assert_eq!(ids.split(' ').count(), 2, "two job ids: {ids}");
    let merged = out.join("merged").join("results.db");
    wait_for(
        "the shards and their merge job",
        600,
        || {
            let queue = cluster.command("squeue").args(["-h"]).output();
            queue.is_ok_and(|q| q.stdout.is_empty()) && merged.is_file()
        },
        &cluster.dir,
    );
    for k in 1..=3 {
        assert!(out.join(format!("shard_{k}")).join("grid.json").is_file());
    }

    // The same grid, unsharded, on this machine.
    let whole = base.join("whole");
    let mut bench = Command::new(pushplan);
    bench.arg("bench").args(scenes.split(' '));
    for (flag, (_, value)) in ["--planners", "--runs", "--time", "--seed", "--shortcut"]
        .iter()
        .zip(settings)
    {
        bench.args([flag, value]);
    }
    output(bench.arg("--out").arg(&whole));
    let (sharded, unsharded) = (
        common::benchmark_runs(&merged),
        common::benchmark_runs(&whole.join("results.db")),
    );
    assert_eq!(sharded.len(), 2 * 2 * 3, "{sharded:?}");
    assert_eq!(sharded, unsharded);

    // A task submitted again with RESUME=1 keeps the runs its shard holds (their logs stay
    // byte for byte: nothing ran again).
    let shard = out.join("shard_1");
    // Each run's log: SHARD/cells/CELL/PLANNER_RUN.log.
    let logs = |dir: &Path| -> Vec<(PathBuf, Vec<u8>)> {
        let mut logs: Vec<(PathBuf, Vec<u8>)> = std::fs::read_dir(dir.join("cells"))
            .unwrap()
            .flatten()
            .flat_map(|cell| std::fs::read_dir(cell.path()).unwrap().flatten())
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|e| e == "log"))
            .map(|p| (p.clone(), std::fs::read(&p).unwrap()))
            .collect();
        logs.sort();
        logs
    };
    let before = logs(&shard);
    assert!(!before.is_empty());
    let resumed = Command::new("bash")
        .arg("examples/slurm/bench.sbatch")
        .env("OUT", &out)
        .env("PUSHPLAN", pushplan)
        .env("SCENES", scenes)
        .envs(settings)
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_ARRAY_TASK_COUNT", "3")
        .env("RESUME", "1")
        .output()
        .unwrap();
    assert!(
        resumed.status.success(),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    assert_eq!(logs(&shard), before, "RESUME=1 ran kept runs again");
    assert!(String::from_utf8_lossy(&resumed.stderr).contains("kept from before"));
    drop(cluster);
    let _ = std::fs::remove_dir_all(&base);
}
