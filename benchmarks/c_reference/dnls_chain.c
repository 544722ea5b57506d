/* Hand-written C99 reference of chainchaos's split engine on the disordered DNLS chain.
 *
 *   H = A + B + C,  A = sum_l a(x_l),  B = -sum_l q_l q_{l+1},  C = -sum_l p_l p_{l+1},
 *   x_l = q_l^2 + p_l^2,  a(x) = eps x/2 + beta x^2/8,  q = p = 0 beyond the ends
 *
 * (docs/conventions.md, "Split models" and "DNLS"). Any three-part scheme given as its table (a
 * step is the stages i = 1..s in turn, stage i the exact flow of part parts[i] (0 = A, 1 = B,
 * 2 = C) for a time coefficients[i] dt), the tangent map in every stage, the deviation vector
 * renormalised every check_every steps and at the end: what
 * chainchaos.engine.split.advance_split does, one trajectory, loop by loop.
 *
 *   A(t): w_l = eps_l + beta_l x_l / 2, g_l = beta_l, (s, c) = (sin w_l t, cos w_l t),
 *         q' = c q + s p,  p' = c p - s q,
 *         shear = t g (q dq + p dp),  dq' = (c dq + s dp) + shear p',  dp' = (c dp - s dq) - shear q'
 *   B(t): p_l += t (q_{l-1} + q_{l+1}),   dp_l += t (dq_{l-1} + dq_{l+1})
 *   C(t): q_l += (-t) (p_{l-1} + p_{l+1}), dq_l += (-t) (dp_{l-1} + dp_{l+1})
 *
 * With width > 1, the square lattice of Nx = N / width sites per line and width lines (site
 * (i, j) is number j Nx + i, docs/conventions.md "Lattices"): B and C add the pair across the
 * lines, (x_{l-Nx} + x_{l+Nx}), to the pair along the line, as the engines do.
 *
 * The sine and cosine are the C library's (glibc's sincos, within 1 ulp), not
 * the engines' kernels.exactmath.sincos (fdlibm's kernels in + - * only, within 1 ulp): enough
 * for a speed reference, and the reason the final states differ from the engines' in the last
 * bits, a difference that grows with the run's length (the dynamics is chaotic). No
 * -ffast-math, so every other operation is the engine's, in its order (-std=c99 keeps gcc from
 * contracting a * b + c into an FMA, as Numba does without fastmath); gcc does not vectorise the
 * library's sincos without -ffast-math, so the A loop calls it once per site.
 *
 * Build: gcc -O3 -march=native -std=c99 -fno-math-errno -o dnls_chain dnls_chain.c -lm
 * Run:   dnls_chain INPUT   with INPUT lines "key v1 v2 ..." (written by benchmarks/dnls_kernel.py):
 *        width (optional, before N; default 1), N, steps, tangent (0/1), check_every, repeats, dt,
 *        stages s, parts (s integers),
 *        coefficients (s values), eps, beta, q, p, dq, dp (N values each).
 * Output: "ns_per_step X" (best of the repeats, each from the input state; the process's CPU
 *        time, as the Python side's time.process_time), "bad_step", "log_growth", and the final
 *        q, p, dq, dp ("key v1 ... vN", %.17g).
 */
#define _GNU_SOURCE /* sincos */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_STAGES 128

static int N, NX, NY = 1, PAD = 1;
static double *eps, *beta, *q0, *p0, *dq0, *dp0, *q, *p, *dq, *dp;

/* The arrays are padded: PAD zeros before the sites PAD..N + PAD - 1 and after them (one on a
 * chain, a line on a square lattice: the neighbours beyond the edges). Restrict-qualified local
 * copies tell gcc that they do not overlap. */
static void rotate(double t, int tangent)
{
    double *restrict Q = q, *restrict P = p, *restrict DQ = dq, *restrict DP = dp;
    const double *restrict E = eps, *restrict G = beta;
    for (int n = PAD; n < N + PAD; n++) {
        double qn = Q[n], pn = P[n];
        double x = qn * qn + pn * pn;
        double w = E[n] + 0.5 * G[n] * x, g = G[n];
        double s, c;
        sincos(w * t, &s, &c);
        double q1 = c * qn + s * pn;
        double p1 = c * pn - s * qn;
        Q[n] = q1;
        P[n] = p1;
        if (tangent) {
            double dqn = DQ[n], dpn = DP[n];
            double shear = t * (g * (qn * dqn + pn * dpn));
            DQ[n] = (c * dqn + s * dpn) + shear * p1;
            DP[n] = (c * dpn - s * dqn) - shear * q1;
        }
    }
}

/* y_l += c (sum of x over l's neighbours) on every site (x = 0 beyond the edges: the padding, and
 * at the ends of a line of the square lattice). */
static void hop(double *restrict Y, const double *restrict X, double c)
{
    if (NY == 1) {
        for (int n = 1; n <= N; n++)
            Y[n] = Y[n] + c * (X[n - 1] + X[n + 1]);
        return;
    }
    for (int j = 0; j < NY; j++) {
        int first = PAD + j * NX;
        for (int n = first; n < first + NX; n++) {
            double left = n > first ? X[n - 1] : 0.0, right = n + 1 < first + NX ? X[n + 1] : 0.0;
            Y[n] = Y[n] + c * ((left + right) + (X[n - NX] + X[n + NX]));
        }
    }
}

static double renormalise(void)
{
    double s = 0.0;
    for (int n = PAD; n < N + PAD; n++)
        s += dq[n] * dq[n] + dp[n] * dp[n];
    double norm = sqrt(s);
    for (int n = PAD; n < N + PAD; n++) {
        dq[n] /= norm;
        dp[n] /= norm;
    }
    return log(norm);
}

/* Integrate n_steps; returns -1, or the number of steps done when the state became non-finite. */
static long integrate(long n_steps, int tangent, long check_every, double dt, int stages, const int *parts,
                      const double *coefficients, double *log_growth)
{
    for (long step = 0; step < n_steps; step++) {
        for (int i = 0; i < stages; i++) {
            double t = coefficients[i] * dt;
            if (parts[i] == 0)
                rotate(t, tangent);
            else if (parts[i] == 1) {
                hop(p, q, t);
                if (tangent)
                    hop(dp, dq, t);
            }
            else {
                hop(q, p, -t);
                if (tangent)
                    hop(dq, dp, -t);
            }
        }
        if ((step + 1) % check_every == 0 || step + 1 == n_steps) {
            double s = 0.0;
            for (int n = PAD; n < N + PAD; n++)
                s += q[n] + p[n];
            if (tangent) {
                *log_growth += renormalise();
                s += dq[PAD];
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
            fprintf(stderr, "dnls_chain: %s needs %d values\n", key, count);
            exit(2);
        }
}

static void print_state(const char *key, const double *v)
{
    printf("%s", key);
    for (int n = PAD; n < N + PAD; n++)
        printf(" %.17g", v[n]);
    printf("\n");
}

static double *padded(void)
{
    double *v = calloc((size_t)N + 2 * (size_t)PAD, sizeof(double)); /* zero padding: the edges */
    if (!v) {
        fprintf(stderr, "dnls_chain: out of memory\n");
        exit(2);
    }
    return v;
}

static double cpu_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
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
    int tangent = 1, stages = 0, parts[MAX_STAGES];
    long n_steps = 0, check_every = 1000, repeats = 1;
    double dt = 0.0, coefficients[MAX_STAGES];
    char key[64];
    while (fscanf(in, "%63s", key) == 1) {
        if (!strcmp(key, "width")) {
            if (N || fscanf(in, "%d", &NY) != 1 || NY < 1) return 2;
        }
        else if (!strcmp(key, "N")) {
            if (N || fscanf(in, "%d", &N) != 1 || N < 1 || N % NY) return 2;
            NX = N / NY;
            PAD = NY > 1 ? NX : 1;
            eps = padded(), beta = padded();
            q0 = padded(), p0 = padded(), dq0 = padded(), dp0 = padded();
            q = padded(), p = padded(), dq = padded(), dp = padded();
        }
        else if (!strcmp(key, "steps")) { if (fscanf(in, "%ld", &n_steps) != 1) return 2; }
        else if (!strcmp(key, "tangent")) { if (fscanf(in, "%d", &tangent) != 1) return 2; }
        else if (!strcmp(key, "check_every")) { if (fscanf(in, "%ld", &check_every) != 1) return 2; }
        else if (!strcmp(key, "repeats")) { if (fscanf(in, "%ld", &repeats) != 1) return 2; }
        else if (!strcmp(key, "stages")) {
            if (fscanf(in, "%d", &stages) != 1 || stages < 1 || stages > MAX_STAGES) return 2;
        }
        else if (!strcmp(key, "dt")) read_values(in, key, &dt, 1);
        else if (!stages) { fprintf(stderr, "dnls_chain: stages must come before %s\n", key); return 2; }
        else if (!strcmp(key, "parts")) {
            for (int i = 0; i < stages; i++)
                if (fscanf(in, "%d", &parts[i]) != 1 || parts[i] < 0 || parts[i] > 2) {
                    fprintf(stderr, "dnls_chain: parts needs %d values 0, 1 or 2\n", stages);
                    return 2;
                }
        }
        else if (!strcmp(key, "coefficients")) read_values(in, key, coefficients, stages);
        else if (!N) { fprintf(stderr, "dnls_chain: N must come before %s\n", key); return 2; }
        else if (!strcmp(key, "eps")) read_values(in, key, eps + PAD, N);
        else if (!strcmp(key, "beta")) read_values(in, key, beta + PAD, N);
        else if (!strcmp(key, "q")) read_values(in, key, q0 + PAD, N);
        else if (!strcmp(key, "p")) read_values(in, key, p0 + PAD, N);
        else if (!strcmp(key, "dq")) read_values(in, key, dq0 + PAD, N);
        else if (!strcmp(key, "dp")) read_values(in, key, dp0 + PAD, N);
        else { fprintf(stderr, "dnls_chain: unknown key %s\n", key); return 2; }
    }
    fclose(in);
    if (!N || n_steps < 1 || check_every < 1 || repeats < 1 || !(dt > 0.0) || !stages) {
        fprintf(stderr, "dnls_chain: need N, stages, parts, coefficients, steps >= 1, check_every >= 1, dt > 0\n");
        return 2;
    }

    size_t bytes = ((size_t)N + 2 * (size_t)PAD) * sizeof(double);
    double best = INFINITY, log_growth = 0.0;
    long bad = -1;
    for (long r = 0; r < repeats; r++) {
        memcpy(q, q0, bytes);
        memcpy(p, p0, bytes);
        memcpy(dq, dq0, bytes);
        memcpy(dp, dp0, bytes);
        log_growth = 0.0;
        double t0 = cpu_ns();
        bad = integrate(n_steps, tangent, check_every, dt, stages, parts, coefficients, &log_growth);
        double ns = cpu_ns() - t0;
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
