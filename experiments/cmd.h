/* Subcommands of the grano program: one file each. Each is a main():
 * it prints, and returns the process exit code (0, 1 run failed, 2 bad input). */
#ifndef GR_CMD_H
#define GR_CMD_H

int cmd_run(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_methods(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_silo_start(int argc, char **argv);
int cmd_silo_flow(int argc, char **argv);
int cmd_course(int argc, char **argv);
int cmd_export(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_advise(int argc, char **argv);
int cmd_plot(int argc, char **argv);
int cmd_movie(int argc, char **argv);

/* Backend-specific benchmarks, called by cmd_bench with argv[0] = method. */
int bench_cd(int argc, char **argv);
int bench_dem(int argc, char **argv);
int bench_dsmc(int argc, char **argv);
int bench_edmd(int argc, char **argv);
int bench_lgca(int argc, char **argv);

#endif
