/* Hand-written C99 reference of chainchaos.integrators.advance for the SRKN_6^b scheme.
 *
 * Same algorithm, operation for operation, as the Numba engine: Blanes & Moan SRKN_6^b
 * (kick b1 drift a1 kick b2 drift a2 kick b3 drift a3 kick b4 drift a3 kick b3 drift a2 kick b2
 * drift a1 kick b1), the force of the last kick of a step reused by the first kick of the next
 * (FSAL), the tangent map applied in every kick and drift, the deviation vector renormalised
 * every check_every steps and at the end. Bond b = 0..N joins beads b-1 and b; the walls are
 * q[0] = q[N+1] = 0 in the padded arrays below, so no branch in the loops.
 *
 *   Hertz: x = max(delta + D, 0), f = A x sqrt(x), k = 1.5 A sqrt(x)
 *   FPUT:  f = D (K2 - D (K3 - D K4)),  k = K2 - D (2 K3 - 3 K4 D)
 *
 * with the compression D = u_{b-1} - u_b, which is q[b] - q[b+1] in the padded arrays.
 *
 * The tangent kick dp_n += c (g_{n-1} - g_n), g_b = k_b (dq_{b-1} - dq_b), forms g on the fly.
 *
 * Build: gcc -O3 -march=native -std=c99 -fno-math-errno -o srkn6b_chain srkn6b_chain.c -lm
 *        (-DNB=... for N != 40). -fno-math-errno only drops the errno write of sqrt, which
 *        otherwise keeps gcc from vectorising the Hertz loop; results are unchanged (no -ffast-math).
 * Run:   srkn6b_chain INPUT   with INPUT lines "key v1 v2 ..." (written by kernel_vs_c.py):
 *        model (0 Hertz, else the FPUT polynomial, e.g. 1), N, steps, tangent (0/1),
 *        check_every, repeats, dt,
 *        A, delta, K2, K3, K4 (N+1 values), inv_mass, q, p, dq, dp (N values).
 * Output: "ns_per_step X" (best of the repeats, each from the input state), "log_growth X",
 *        and the final q, p, dq, dp ("key v1 ... vN", %.17g).
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef NB
#define NB 40
#endif

static double A[NB + 1], delta[NB + 1], K2[NB + 1], K3[NB + 1], K4[NB + 1], inv_mass[NB + 2];
static double q0[NB + 2], p0[NB + 2], dq0[NB + 2], dp0[NB + 2];  /* input state, beads 1..NB */
static double q[NB + 2], p[NB + 2], dq[NB + 2], dp[NB + 2];      /* q[0] = q[NB+1] = 0: walls */
static double f[NB + 1], k[NB + 1];  /* bond force and stiffness df/dD */

static void forces_hertz(int tangent)
{
    if (tangent) {
        for (int b = 0; b <= NB; b++) {
            double x = delta[b] + q[b] - q[b + 1];
            x = x > 0.0 ? x : 0.0;
            double s = sqrt(x);
            f[b] = A[b] * x * s;
            k[b] = 1.5 * A[b] * s;
        }
    } else {
        for (int b = 0; b <= NB; b++) {
            double x = delta[b] + q[b] - q[b + 1];
            x = x > 0.0 ? x : 0.0;
            f[b] = A[b] * x * sqrt(x);
        }
    }
}

static void forces_fput(int tangent)
{
    if (tangent) {
        for (int b = 0; b <= NB; b++) {
            double D = q[b] - q[b + 1];
            f[b] = D * (K2[b] - D * (K3[b] - D * K4[b]));
            k[b] = K2[b] - D * (2.0 * K3[b] - 3.0 * K4[b] * D);
        }
    } else {
        for (int b = 0; b <= NB; b++) {
            double D = q[b] - q[b + 1];
            f[b] = D * (K2[b] - D * (K3[b] - D * K4[b]));
        }
    }
}

static void kick(double c, int tangent)
{
    if (tangent) {
        for (int n = 1; n <= NB; n++) {
            p[n] += c * (f[n - 1] - f[n]);
            dp[n] += c * (k[n - 1] * (dq[n - 1] - dq[n]) - k[n] * (dq[n] - dq[n + 1]));
        }
    } else {
        for (int n = 1; n <= NB; n++)
            p[n] += c * (f[n - 1] - f[n]);
    }
}

static void drift(double c, int tangent)
{
    for (int n = 1; n <= NB; n++)
        q[n] += c * inv_mass[n] * p[n];
    if (tangent)
        for (int n = 1; n <= NB; n++)
            dq[n] += c * inv_mass[n] * dp[n];
}

static double renormalise(void)
{
    double s = 0.0;
    for (int n = 1; n <= NB; n++)
        s += dq[n] * dq[n] + dp[n] * dp[n];
    double norm = sqrt(s);
    for (int n = 1; n <= NB; n++) {
        dq[n] /= norm;
        dp[n] /= norm;
    }
    return log(norm);
}

/* Integrate n_steps; returns -1, or the number of steps done when the state became non-finite. */
static long integrate(int model, long n_steps, int tangent, long check_every, double dt,
                      double *log_growth)
{
    const double b1 = 0.082984406417405200, b2 = 0.39630980149836800, b3 = -0.039056304922348600;
    const double a1 = 0.24529895718427100, a2 = 0.60487266571108000;
    const double kicks[7] = {b1, b2, b3, 1 - 2 * (b1 + b2 + b3), b3, b2, b1};
    const double a3 = 0.5 - a1 - a2;
    const double drifts[6] = {a1, a2, a3, a3, a2, a1};
    int force_valid = 0;
    for (long step = 0; step < n_steps; step++) {
        for (int i = 0; i < 7; i++) {
            if (!force_valid) {
                if (model == 0)
                    forces_hertz(tangent);
                else
                    forces_fput(tangent);
                force_valid = 1;
            }
            kick(kicks[i] * dt, tangent);
            if (i < 6) {
                drift(drifts[i] * dt, tangent);
                force_valid = 0;
            }
        }
        if ((step + 1) % check_every == 0 || step + 1 == n_steps) {
            double s = 0.0;
            for (int n = 1; n <= NB; n++)
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
            fprintf(stderr, "srkn6b_chain: %s needs %d values\n", key, count);
            exit(2);
        }
}

static void print_state(const char *key, const double *v)
{
    printf("%s", key);
    for (int n = 1; n <= NB; n++)
        printf(" %.17g", v[n]);
    printf("\n");
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
    int model = 0, N = 0, tangent = 1;
    long n_steps = 0, check_every = 1000, repeats = 1;
    double dt = 0.0;
    char key[64];
    while (fscanf(in, "%63s", key) == 1) {
        if (!strcmp(key, "model")) { if (fscanf(in, "%d", &model) != 1) return 2; }
        else if (!strcmp(key, "N")) { if (fscanf(in, "%d", &N) != 1) return 2; }
        else if (!strcmp(key, "steps")) { if (fscanf(in, "%ld", &n_steps) != 1) return 2; }
        else if (!strcmp(key, "tangent")) { if (fscanf(in, "%d", &tangent) != 1) return 2; }
        else if (!strcmp(key, "check_every")) { if (fscanf(in, "%ld", &check_every) != 1) return 2; }
        else if (!strcmp(key, "repeats")) { if (fscanf(in, "%ld", &repeats) != 1) return 2; }
        else if (!strcmp(key, "dt")) read_values(in, key, &dt, 1);
        else if (N != NB) { fprintf(stderr, "srkn6b_chain: built for N = %d, input N = %d\n", NB, N); return 2; }
        else if (!strcmp(key, "A")) read_values(in, key, A, NB + 1);
        else if (!strcmp(key, "delta")) read_values(in, key, delta, NB + 1);
        else if (!strcmp(key, "K2")) read_values(in, key, K2, NB + 1);
        else if (!strcmp(key, "K3")) read_values(in, key, K3, NB + 1);
        else if (!strcmp(key, "K4")) read_values(in, key, K4, NB + 1);
        else if (!strcmp(key, "inv_mass")) read_values(in, key, inv_mass + 1, NB);
        else if (!strcmp(key, "q")) read_values(in, key, q0 + 1, NB);
        else if (!strcmp(key, "p")) read_values(in, key, p0 + 1, NB);
        else if (!strcmp(key, "dq")) read_values(in, key, dq0 + 1, NB);
        else if (!strcmp(key, "dp")) read_values(in, key, dp0 + 1, NB);
        else { fprintf(stderr, "srkn6b_chain: unknown key %s\n", key); return 2; }
    }
    fclose(in);
    if (N != NB || n_steps < 1 || check_every < 1 || repeats < 1 || !(dt > 0.0)) {
        fprintf(stderr, "srkn6b_chain: need N = %d, steps >= 1, check_every >= 1, dt > 0\n", NB);
        return 2;
    }

    double best = INFINITY, log_growth = 0.0;
    long bad = -1;
    for (long r = 0; r < repeats; r++) {
        memcpy(q, q0, sizeof q);
        memcpy(p, p0, sizeof p);
        memcpy(dq, dq0, sizeof dq);
        memcpy(dp, dp0, sizeof dp);
        log_growth = 0.0;
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        bad = integrate(model, n_steps, tangent, check_every, dt, &log_growth);
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
