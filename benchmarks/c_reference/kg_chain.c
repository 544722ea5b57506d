/* Hand-written C99 reference of chainchaos's engines on the disordered Klein-Gordon chain.
 *
 *   H = sum_n [ p_n^2/2 + eps_n u_n^2/2 + u_n^4/4 ] + sum_b K2_b (u_{b-1} - u_b)^2 / 2,  u_0 = u_{N+1} = 0
 *
 * Any symmetric splitting given as its tables (kick c_0 .. c_s, drift d_1 .. d_s: a step is
 * kick c_0, then drift d_i, kick c_i for i = 1..s; a zero kick is skipped), the force of a step's
 * last kick reused by the next step's first (FSAL), the tangent map in every kick and drift, the
 * deviation vector renormalised every check_every steps and at the end: what
 * chainchaos.engine.integrators.advance does, one trajectory, loop by loop.
 *
 *   bond b = 0..N joins beads b-1 and b:  f_b = K2_b D_b,  D_b = u_{b-1} - u_b  (k_b = K2_b)
 *   site n:  w'(u) = u (eps_n + u^2),  w''(u) = eps_n + 3 u^2
 *   kick(c):  p_n += c (f_{n-1} - f_n - w'(u_n)),
 *             dp_n += c (k_{n-1} (dq_{n-1} - dq_n) - k_n (dq_n - dq_{n+1}) - w''(u_n) dq_n)
 *   drift(c): u_n += c p_n,  dq_n += c dp_n   (masses 1)
 *
 * Build: gcc -O3 -march=native -std=c99 -fno-math-errno -o kg_chain kg_chain.c -lm
 * Run:   kg_chain INPUT   with INPUT lines "key v1 v2 ..." (written by benchmarks/kg_kernel.py):
 *        N, steps, tangent (0/1), check_every, repeats, dt, stages s, kicks (s+1 values),
 *        drifts (s values), K2 (N+1 values), eps, q, p, dq, dp (N values).
 * Output: "ns_per_step X" (best of the repeats, each from the input state), "bad_step", "log_growth",
 *        and the final q, p, dq, dp ("key v1 ... vN", %.17g).
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int N;
static double *K2, *eps, *q0, *p0, *dq0, *dp0, *q, *p, *dq, *dp, *f;

/* The arrays are globals; restrict-qualified local copies tell gcc they do not overlap, so that
 * it vectorises the loops as it does for the fixed-size arrays of srkn6b_chain.c. */
static void forces(void)
{
    double *restrict F = f;
    const double *restrict Q = q, *restrict K = K2;
    for (int b = 0; b <= N; b++)
        F[b] = K[b] * (Q[b] - Q[b + 1]);
}

static void kick(double c, int tangent)
{
    double *restrict P = p, *restrict DP = dp;
    const double *restrict F = f, *restrict Q = q, *restrict DQ = dq, *restrict K = K2, *restrict E = eps;
    for (int n = 1; n <= N; n++) {
        double u = Q[n];
        P[n] += c * (F[n - 1] - F[n] - u * (E[n] + u * u));
    }
    if (tangent)
        for (int n = 1; n <= N; n++)
            DP[n] += c * (K[n - 1] * (DQ[n - 1] - DQ[n]) - K[n] * (DQ[n] - DQ[n + 1]) - (E[n] + 3.0 * (Q[n] * Q[n])) * DQ[n]);
}

static void drift(double c, int tangent)
{
    double *restrict Q = q, *restrict DQ = dq;
    const double *restrict P = p, *restrict DP = dp;
    for (int n = 1; n <= N; n++)
        Q[n] += c * P[n];
    if (tangent)
        for (int n = 1; n <= N; n++)
            DQ[n] += c * DP[n];
}

static double renormalise(void)
{
    double s = 0.0;
    for (int n = 1; n <= N; n++)
        s += dq[n] * dq[n] + dp[n] * dp[n];
    double norm = sqrt(s);
    for (int n = 1; n <= N; n++) {
        dq[n] /= norm;
        dp[n] /= norm;
    }
    return log(norm);
}

/* Integrate n_steps; returns -1, or the number of steps done when the state became non-finite. */
static long integrate(long n_steps, int tangent, long check_every, double dt, int stages, const double *kicks,
                      const double *drifts, double *log_growth)
{
    int force_valid = 0;
    for (long step = 0; step < n_steps; step++) {
        for (int i = 0; i <= stages; i++) {
            if (i > 0) {
                drift(drifts[i - 1] * dt, tangent);
                force_valid = 0;
            }
            if (kicks[i] != 0.0) {
                if (!force_valid) {
                    forces();
                    force_valid = 1;
                }
                kick(kicks[i] * dt, tangent);
            }
        }
        if ((step + 1) % check_every == 0 || step + 1 == n_steps) {
            double s = 0.0;
            for (int n = 1; n <= N; n++)
                s += q[n] + p[n];
            if (tangent) {
                *log_growth += renormalise();
                s += dq[1];
            }
            if (!isfinite(s))
                return step + 1;
        }
    }
    return -1;
}

static void read_values(FILE *in, const char *key, double *dst, int count)
{
    for (int i = 0; i < count; i++)
        if (fscanf(in, "%lf", &dst[i]) != 1) {
            fprintf(stderr, "kg_chain: %s needs %d values\n", key, count);
            exit(2);
        }
}

static void print_state(const char *key, const double *v)
{
    printf("%s", key);
    for (int n = 1; n <= N; n++)
        printf(" %.17g", v[n]);
    printf("\n");
}

static double *padded(void)
{
    double *v = calloc((size_t)N + 2, sizeof(double));  /* v[0] = v[N+1] = 0: the walls */
    if (!v) {
        fprintf(stderr, "kg_chain: out of memory\n");
        exit(2);
    }
    return v;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s INPUT\n", argv[0]);
        return 2;
    }
    FILE *in = fopen(argv[1], "r");
    if (!in) {
        perror(argv[1]);
        return 2;
    }
    int tangent = 1, stages = 0;
    long n_steps = 0, check_every = 1000, repeats = 1;
    double dt = 0.0, kicks[32], drifts[32];
    char key[64];
    while (fscanf(in, "%63s", key) == 1) {
        if (!strcmp(key, "N")) {
            if (fscanf(in, "%d", &N) != 1 || N < 1) return 2;
            K2 = padded(), eps = padded(), f = padded();
            q0 = padded(), p0 = padded(), dq0 = padded(), dp0 = padded();
            q = padded(), p = padded(), dq = padded(), dp = padded();
        }
        else if (!strcmp(key, "steps")) { if (fscanf(in, "%ld", &n_steps) != 1) return 2; }
        else if (!strcmp(key, "tangent")) { if (fscanf(in, "%d", &tangent) != 1) return 2; }
        else if (!strcmp(key, "check_every")) { if (fscanf(in, "%ld", &check_every) != 1) return 2; }
        else if (!strcmp(key, "repeats")) { if (fscanf(in, "%ld", &repeats) != 1) return 2; }
        else if (!strcmp(key, "stages")) { if (fscanf(in, "%d", &stages) != 1 || stages < 1 || stages > 30) return 2; }
        else if (!strcmp(key, "dt")) read_values(in, key, &dt, 1);
        else if (!strcmp(key, "kicks")) read_values(in, key, kicks, stages + 1);
        else if (!strcmp(key, "drifts")) read_values(in, key, drifts, stages);
        else if (!N) { fprintf(stderr, "kg_chain: N must come before %s\n", key); return 2; }
        else if (!strcmp(key, "K2")) read_values(in, key, K2, N + 1);
        else if (!strcmp(key, "eps")) read_values(in, key, eps + 1, N);
        else if (!strcmp(key, "q")) read_values(in, key, q0 + 1, N);
        else if (!strcmp(key, "p")) read_values(in, key, p0 + 1, N);
        else if (!strcmp(key, "dq")) read_values(in, key, dq0 + 1, N);
        else if (!strcmp(key, "dp")) read_values(in, key, dp0 + 1, N);
        else { fprintf(stderr, "kg_chain: unknown key %s\n", key); return 2; }
    }
    fclose(in);
    if (!N || n_steps < 1 || check_every < 1 || repeats < 1 || !(dt > 0.0) || !stages) {
        fprintf(stderr, "kg_chain: need N, stages, steps >= 1, check_every >= 1, dt > 0\n");
        return 2;
    }

    size_t bytes = ((size_t)N + 2) * sizeof(double);
    double best = INFINITY, log_growth = 0.0;
    long bad = -1;
    for (long r = 0; r < repeats; r++) {
        memcpy(q, q0, bytes);
        memcpy(p, p0, bytes);
        memcpy(dq, dq0, bytes);
        memcpy(dp, dp0, bytes);
        log_growth = 0.0;
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        bad = integrate(n_steps, tangent, check_every, dt, stages, kicks, drifts, &log_growth);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double ns = 1e9 * (double)(t1.tv_sec - t0.tv_sec) + (double)(t1.tv_nsec - t0.tv_nsec);
        if (ns < best)
            best = ns;
    }
    printf("ns_per_step %.6g\n", best / (double)n_steps);
    printf("bad_step %ld\n", bad);
    printf("log_growth %.17g\n", log_growth);
    print_state("q", q);
    print_state("p", p);
    print_state("dq", dq);
    print_state("dp", dp);
    return 0;
}
